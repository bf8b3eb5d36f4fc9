#pragma once
// The error a user can cause (campaign file, options, folder state): one line naming what is
// wrong and what to do; criticality-campaign exits with 2.
#include <stdexcept>
#include <string>

namespace criticality::campaign {

class CampaignError : public std::runtime_error {
 public:
  explicit CampaignError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace criticality::campaign
