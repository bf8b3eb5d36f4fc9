#pragma once
/** @file Exceptions the estimator throws for input a user can get wrong. */
#include <stdexcept>
#include <string>

namespace criticality {

/** Invalid scene or parameters: the message names the field and its value. */
class InputError : public std::invalid_argument {
 public:
  explicit InputError(const std::string& what) : std::invalid_argument(what) {}
};

/** The requested work does not fit the configured limits (e.g. Params::max_memory_bytes). */
class WorkloadError : public std::runtime_error {
 public:
  explicit WorkloadError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace criticality
