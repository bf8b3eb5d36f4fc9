// sumo-criticality: what a SUMO user runs instead of `sumo`. See --help.
#include <csignal>
#include <iostream>
#include <string>

#include "criticality/errors.h"
#include "plugin/driver.h"
#include "plugin/driver_options.h"
#include "plugin/results_db.h"
#include "plugin/sumo_world.h"

namespace {
// Errors are one line, whatever SUMO put in its message.
std::string OneLine(std::string s) {
  for (char& c : s) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return s;
}
}  // namespace

int main(int argc, char** argv) {
  using namespace criticality::plugin;
  // A SUMO that goes away under --connect must be an error, not a silent SIGPIPE death.
  std::signal(SIGPIPE, SIG_IGN);
  try {
    const ParseOutcome parsed = ParseDriverOptions(argc, argv);
    if (parsed.exit_now) return parsed.exit_code;
    RunDriver(parsed.options, std::cout);
    return 0;
  } catch (const std::invalid_argument& e) {  // options, scenario content, estimator input
    std::cerr << "sumo-criticality: error: " << OneLine(e.what()) << "\n";
    return 2;
  } catch (const SumoError& e) {
    std::cerr << "sumo-criticality: SUMO error: " << OneLine(e.what()) << "\n";
    return 3;
  } catch (const ResultsError& e) {
    std::cerr << "sumo-criticality: error: " << OneLine(e.what()) << "\n";
    return 4;
  } catch (const EgoError& e) {
    std::cerr << "sumo-criticality: error: " << OneLine(e.what()) << "\n";
    return 5;
  } catch (const std::exception& e) {
    std::cerr << "sumo-criticality: internal error: " << OneLine(e.what()) << "\n";
    return 1;
  }
}
