// SumoWorld on libtraci: attaches to a SUMO or sumo-gui started with --remote-port.
#include <libsumo/libtraci.h>

#include <algorithm>

#define CRIT_SUMO libtraci
#define CRIT_SUMO_NO_GET_COLLISIONS 1
#include "plugin/sumo_world_impl.inc"

namespace criticality::plugin {

std::unique_ptr<SumoWorld> ConnectLibtraci(const std::string& host, int port) {
  try {
    libtraci::Simulation::init(port, 30, host);
  } catch (const std::exception& e) {
    throw SumoError("cannot connect to SUMO at " + host + ":" + std::to_string(port) + ": " +
                    e.what() + " (start it with --remote-port " + std::to_string(port) + ")");
  }
  return std::make_unique<World>();
}

}  // namespace criticality::plugin
