#pragma once
// Which side a network drives on. SUMO numbers an edge's lanes from the kerb: lane 0 is the
// rightmost in right-hand traffic and the leftmost in a left-hand network (netconvert
// --lefthand), so the lane with the next higher index lies left of a lane in the one and right
// of it in the other, and the opposite direction's lanes lie beyond the highest index: on the
// left, or on the right. Read from the lanes' geometry, so that it needs neither the network
// file nor an option.
#include "plugin/network/road_network.h"

namespace criticality::plugin {

/** Whether `network` drives on the left: on most of its first 25 normal edges with two lanes or
 *  more, lane 1's centre lies right of lane 0's (at the middle of lane 0). A network without
 *  such an edge is taken to drive on the right. */
bool LeftHandTraffic(RoadNetwork& network);

}  // namespace criticality::plugin
