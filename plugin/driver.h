#pragma once
// The co-simulation loop: step SUMO, extract each ego's scene, estimate, write back (warning,
// criticality parameter, optional braking), record everything in the results database.
#include <ostream>
#include <stdexcept>
#include <string>

#include "plugin/driver_options.h"

namespace criticality::plugin {

/** A problem with an ego: never departed, teleported. */
class EgoError : public std::runtime_error {
 public:
  explicit EgoError(const std::string& what) : std::runtime_error(what) {}
};

/** Runs the simulation to its end. Prints the one-line JSON summary to `summary`.
 *  @throws SumoError, ResultsError, EgoError, InputError; the database then keeps every step
 *  completed before the failure and its run row says what failed. */
void RunDriver(const DriverOptions& options, std::ostream& summary);

}  // namespace criticality::plugin
