#pragma once
// Which objects surround each ego when the whole network is read (--all-vehicles): a grid of
// square cells `cell_m` wide over the objects' centres; an ego's neighbours are the objects in
// its cell and the 8 around it, in the order of `objects` (so a scene does not depend on the
// grid). With cells at least one read range wide this is a superset of the objects within the
// range; the scenes stage applies the exact range. A vehicle longer than a cell is in every cell
// along its body (straight back from its front). Objects with a non-finite position fall in the
// cell at the origin.
#include "plugin/sumo/sumo_reports.h"

namespace criticality::plugin {

/** Fills every Ego::nearby of `s` from the grid. */
void FindNeighbours(double cell_m, SumoSurroundings* s);

}  // namespace criticality::plugin
