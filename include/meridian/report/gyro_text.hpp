#pragma once
/// \file gyro_text.hpp
/// Plain-text reports of gyro results for the terminal and for filing.
/// Angles in DMS, σ in arc-seconds.

#include <string>
#include <vector>

#include "meridian/gyro/campaign.hpp"
#include "meridian/gyro/determination.hpp"
#include "meridian/gyro/orientations.hpp"
#include "meridian/gyro/reduce.hpp"
#include "meridian/gyro/transit_calibration.hpp"
#include "meridian/report/format.hpp"

namespace meridian::report {

/// One determination (`index` is 0-based, printed 1-based): every method's
/// β, ΔN, N_G and σ, the recommended one, the zero-position correction, warnings.
/// Angles are written by `f` (the book's angle unit; DMS by default).
std::string determination_text(const gyro::DeterminationResult& r, int index, const AngleFormat& f = AngleFormat());

/// `meridian gyro reduce`: a header line (file, count, λ, τ), the
/// instrument notes, then every determination.
std::string reduce_text(const gyro::ReduceResult& r, const AngleFormat& f = AngleFormat());

/// `meridian gyro campaign`: stations, calibration, the line's
/// determinations, the azimuth chain, checks, notes and warnings.
std::string campaign_text(const gyro::CampaignResult& r, const AngleFormat& f = AngleFormat());

/// One check: "name: value unit (limit L unit)" ("at least" for a minimum).
std::string check_statement(const gyro::Check& k);

/// One check as a line: "[PASS] " or "[FAIL] " + check_statement.
std::string check_text(const gyro::Check& k);

/// `meridian gyro orientations`: each orientation's grid azimuth (and file),
/// the mean with σ, and the checks.
std::string orientations_text(const gyro::OrientationsResult& r, const AngleFormat& f = AngleFormat());

/// `meridian gyro transit-factor`.
std::string transit_factor_text(const gyro::TransitFactorCalibration& c);

}  // namespace meridian::report
