// sumo-criticality: what a SUMO user runs instead of `sumo`. See --help.
#include <csignal>
#include <iostream>
#include <string>

#include "plugin/driver.h"
#include "plugin/driver_options.h"
#include "plugin/run_summary.h"

int main(int argc, char** argv) {
  using namespace criticality::plugin;
  // A SUMO that goes away under --connect must be an error, not a silent SIGPIPE death.
  std::signal(SIGPIPE, SIG_IGN);
  RunSummary summary;
  int code = kExitInternal;
  try {
    const ParseOutcome parsed = ParseDriverOptions(argc, argv);
    if (parsed.exit_now) return parsed.exit_code;  // --help, --version: not a run
    code = RunDriver(parsed.options, &summary);
  } catch (...) {  // option parsing (RunDriver never throws)
    summary.exit_code = code = ExitCodeFor(std::current_exception(), &summary.error);
    summary.status = "failed";
    summary.end_reason = "error";
  }
  if (!summary.error.empty()) std::cerr << "sumo-criticality: error: " << summary.error << "\n";
  // The last line of standard output, on every exit of a run.
  std::cout << SummaryJson(summary) << std::endl;
  return code;
}
