#pragma once
/// \file gyro_text.hpp
/// Plain-text reports of gyro results for the terminal and for filing.
/// Angles in DMS, σ in arc-seconds.

#include <string>
#include <vector>

#include "meridian/gyro/campaign.hpp"
#include "meridian/gyro/determination.hpp"

namespace meridian::report {

std::string determination_text(const gyro::DeterminationResult& r, int index);
std::string campaign_text(const gyro::CampaignResult& r);

}  // namespace meridian::report
