// SumoWorld on libsumo: SUMO runs inside this process.
#include <libsumo/libsumo.h>

#include <algorithm>

#define CRIT_SUMO libsumo
#include "plugin/sumo_world_impl.inc"

namespace criticality::plugin {

std::unique_ptr<SumoWorld> StartLibsumo(const std::vector<std::string>& args) {
  try {
    libsumo::Simulation::load(args);
  } catch (const libsumo::FatalTraCIError& e) {
    throw SumoError(std::string("loading SUMO failed: ") + e.what());
  } catch (const libsumo::TraCIException& e) {
    throw SumoError(std::string("loading SUMO failed: ") + e.what());
  } catch (const std::exception& e) {
    throw SumoError(std::string("loading SUMO failed: ") + e.what());
  }
  return std::make_unique<World>();
}

}  // namespace criticality::plugin
