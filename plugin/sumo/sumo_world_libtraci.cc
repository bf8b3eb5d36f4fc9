// SumoWorld on libtraci: attaches to a SUMO or sumo-gui started with --remote-port.
#include <libsumo/libtraci.h>

#include <algorithm>

#define CRIT_SUMO libtraci
#define CRIT_SUMO_NO_GET_COLLISIONS 1
#include "plugin/sumo/sumo_world_impl.inc"

namespace criticality::plugin {

std::unique_ptr<SumoWorld> ConnectLibtraci(const std::string& host, int port) {
  try {
    // A few retries (one per second): a SUMO just started may not listen yet, and nothing
    // listening must fail fast.
    libtraci::Simulation::init(port, 4, host);
  } catch (const std::exception& e) {
    throw SumoError("cannot connect to SUMO at " + host + ":" + std::to_string(port) +
                    " within 4 s (libtraci: " + e.what() + "); start SUMO with --remote-port " +
                    std::to_string(port) + ", or check HOST:PORT");
  }
  return std::make_unique<World>();
}

}  // namespace criticality::plugin
