#pragma once
// The driver's exit codes (plugin/README.md) and the one place that maps an error to one.
#include <exception>
#include <string>

namespace criticality::plugin {

enum ExitCode : int {
  kExitDone = 0,
  kExitInternal = 1,
  kExitBadInput = 2,  ///< std::invalid_argument: options, config file, scenario, estimator input
  kExitSumo = 3,      ///< SumoError: load, connection, SUMO went away
  kExitResults = 4,   ///< ResultsError: the results cannot be written
  kExitEgo = 5,       ///< EgoError: a named ego SUMO never loads, or a person
  kExitSigint = 130,
  kExitSigterm = 143,
};

/** The exit code and one-line message for an exception escaping a run or option parsing. */
int ExitCodeFor(std::exception_ptr error, std::string* message);

}  // namespace criticality::plugin
