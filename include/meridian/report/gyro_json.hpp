#pragma once
/// \file gyro_json.hpp
/// JSON views of gyro results (the `--json` output of the CLI). Angles are
/// decimal degrees (`*_deg`) or arc-seconds (`*_arcsec`); a σ that cannot be
/// stated is null. The keys are a stable contract for scripts; see
/// docs/file-formats.md.

#include <nlohmann/json.hpp>

#include <string>

#include "meridian/gyro/campaign.hpp"
#include "meridian/gyro/determination.hpp"
#include "meridian/gyro/orientations.hpp"
#include "meridian/gyro/reduce.hpp"
#include "meridian/gyro/transit_calibration.hpp"

namespace meridian::report {

/// One method's result: method, north_reading_deg, sigma_arcsec and, for
/// non-tracking, beta_div, delta_n_arcsec; plus details.
nlohmann::json method_to_json(const gyro::MethodResult& r, gyro::Mode mode);

/// One determination: mode, method, the primary method's keys, and with
/// method "all" the array `results` (one entry per applicable method).
nlohmann::json determination_to_json(const gyro::DeterminationResult& r);

/// `meridian gyro reduce --json`: file (ReduceInput::file), torsion_ratio
/// {value, sigma}, notes, determinations.
nlohmann::json reduce_to_json(const gyro::ReduceResult& r);

/// A whole campaign.
nlohmann::json campaign_to_json(const gyro::CampaignResult& r);

/// `meridian gyro orientations --json`: grid_azimuths, mean (deg, dms,
/// sigma_arcsec), checks, notes.
nlohmann::json orientations_to_json(const gyro::OrientationsResult& r);

/// `meridian gyro transit-factor --json` (factors in ″/(div·s)).
nlohmann::json transit_factor_to_json(const gyro::TransitFactorCalibration& c);

}  // namespace meridian::report
