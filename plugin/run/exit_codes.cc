#include "plugin/run/exit_codes.h"

#include <stdexcept>

#include "plugin/observe/observe_stage.h"
#include "plugin/record/results_db.h"
#include "plugin/sumo/sumo_world.h"

namespace criticality::plugin {
namespace {

std::string OneLine(std::string s) {
  for (char& c : s) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return s;
}

}  // namespace

int ExitCodeFor(std::exception_ptr error, std::string* message) {
  try {
    std::rethrow_exception(error);
  } catch (const std::invalid_argument& e) {  // options, scenario content, estimator input
    *message = OneLine(e.what());
    return kExitBadInput;
  } catch (const SumoError& e) {
    *message = "SUMO error: " + OneLine(e.what());
    return kExitSumo;
  } catch (const ResultsError& e) {
    *message = OneLine(e.what());
    return kExitResults;
  } catch (const EgoError& e) {
    *message = OneLine(e.what());
    return kExitEgo;
  } catch (const std::exception& e) {
    *message = "internal error: " + OneLine(e.what());
    return kExitInternal;
  } catch (...) {
    *message = "internal error: unknown exception";
    return kExitInternal;
  }
}

}  // namespace criticality::plugin
