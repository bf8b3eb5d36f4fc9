// sumo-criticality: what a SUMO user runs instead of `sumo`. See --help.
#include <csignal>
#include <iostream>
#include <string>

#include "plugin/options/driver_options.h"
#include "plugin/run/co_simulation.h"
#include "plugin/run/exit_codes.h"
#include "plugin/run/run_summary.h"
#include "plugin/sumo/sumo_world.h"

namespace {

using namespace criticality::plugin;

// SUMO in this process (libsumo), or the running one at --connect (libtraci).
std::unique_ptr<SumoWorld> OpenSumo(const RunConfig& run) {
  if (!run.connect.empty()) {
    const auto colon = run.connect.rfind(':');  // validated by ParseDriverOptions
    return ConnectLibtraci(run.connect.substr(0, colon), std::stoi(run.connect.substr(colon + 1)));
  }
  std::vector<std::string> args{"-c",   run.sumo_config,    "--no-step-log",
                                "true", "--xml-validation", "never"};
  args.insert(args.end(), run.sumo_args.begin(), run.sumo_args.end());
  return StartLibsumo(args);
}

}  // namespace

int main(int argc, char** argv) {
  // A SUMO that goes away under --connect must be an error, not a silent SIGPIPE death.
  std::signal(SIGPIPE, SIG_IGN);
  RunSummary summary;
  int code = kExitInternal;
  try {
    const ParseOutcome parsed = ParseDriverOptions(argc, argv);
    if (parsed.exit_now) return parsed.exit_code;  // --help, --version: not a run
    code = RunDriver(parsed.options, &summary, OpenSumo);
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
