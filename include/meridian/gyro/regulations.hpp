#pragma once
/// \file regulations.hpp
/// The field rules for an orientation with a tape-suspended gyro-theodolite
/// of the Chinese coal-mine surveying regulations (《煤矿测量规程》, as taught
/// in the mine-surveying textbooks; gyro-theodolite spec §7.1), as limits per
/// accuracy class. Every limit can be overridden in a campaign file under
/// `tolerances:`; the report shows each check with its value, limit, source
/// and PASS/FAIL.
///
/// | rule                                             | 5″ class | 15″ class | 25″ class |
/// |--------------------------------------------------|----------|-----------|-----------|
/// | tape zero position |α_p| (motor off)             | 0.5 div  | 0.5 div   | 0.5 div   |
/// | zero position after − before                     | 0.5 div  | 0.5 div   | 0.5 div   |
/// | any two runs on the line (gyro azimuths)         | 10″      | 40″       | 70″       |
/// | instrument constants, any two runs               | 10″      | 40″       | 70″       |
/// | instrument constant, before − after means        | 15″      | 40″       | 70″       |
/// | two independent orientations, difference         | 15″      | 40″       | 60″       |
/// | two independent orientations, σ of their mean    | 4″       | 10″       | 15″       |
/// | programme (runs before / on the line / after)    | ≥ 2/2/2 (3-2-3 recommended)         |
///
/// The 15″ and 25″ columns are the regulations'. The 5″ column holds the
/// project limits commonly applied to gyro total stations (spec §7.1: runs
/// within 10″, before/after means within 15″); its orientation limits are
/// Meridian's choice, scaled from the 15″ class (40″ → 15″, 10″ → 4″).
/// A class is the first column whose value is ≥ the instrument's nominal
/// class; instruments worse than 25″ get the 25″ limits scaled by class/25.
/// Meridian's own plausibility limits (not regulations): the known line's
/// given azimuth against the azimuth from its coordinates (max(3σ, class)),
/// and the size of the instrument constant (|E| ≤ 10′).

#include <optional>
#include <string>

namespace meridian::gyro {

/// Limits of the checks of one orientation, in radians (angles) or
/// divisions (zero position).
struct RegulationLimits {
  double accuracy_class_arcsec = 15.0;      ///< the class the limits were taken for
  double zero_position_div = 0.5;           ///< |α_p| of every motor-off run
  double zero_position_drift_div = 0.5;     ///< |α_p(after) − α_p(before)| of a run
  double run_difference_rad = 0.0;          ///< any two gyro azimuths on the line
  double constant_difference_rad = 0.0;     ///< any two instrument constants on the known line
  double constant_means_rad = 0.0;          ///< before − after means of the instrument constant
  double orientation_difference_rad = 0.0;  ///< two independent orientations of one line
  double orientation_mean_sigma_rad = 0.0;  ///< σ of the mean of two orientations
  int min_runs_before = 2, min_runs_line = 2, min_runs_after = 2;  ///< programme
  double instrument_constant_max_rad = 0.0; ///< plausibility bound on |E|
  /// σ of one tracking reversal reading for a run that books none (Meridian's default,
  /// class/3: 5″ for a 15″ class), so that every tracking run's readings are checked.
  double default_reading_sigma_rad = 0.0;
  std::string source;                       ///< where the limits come from (shown in reports)
};

/// The limits for an instrument of nominal class `accuracy_class_arcsec`
/// (> 0, finite; InputError otherwise). See the table above.
RegulationLimits regulation_limits(double accuracy_class_arcsec);

/// Limits set in a campaign file (`tolerances:`); unset values come from
/// the instrument's class.
struct Tolerances {
  std::optional<double> determination_difference_rad;        ///< any two runs on the line
  /// Any two instrument constants, and (unless instrument_constant_means_rad
  /// is set) the before − after means.
  std::optional<double> instrument_constant_difference_rad;
  std::optional<double> instrument_constant_means_rad;       ///< before − after means
  std::optional<double> orientation_difference_rad;          ///< two independent orientations
  std::optional<double> orientation_mean_sigma_rad;          ///< σ of their mean
  std::optional<double> zero_position_div;                   ///< zero position drift after − before
  std::optional<double> zero_position_limit_div;             ///< |α_p| of a motor-off run
  std::optional<double> known_azimuth_coordinates_rad;       ///< given vs coordinate azimuth of the known line
  /// The line's grid azimuth from the gyro against the azimuth of its end points' coordinates
  /// (gyro − traverse); default the class's limit for two independent orientations.
  std::optional<double> line_coordinates_rad;
  std::optional<double> instrument_constant_max_rad;         ///< |E|
};

/// The class limits with the file's overrides applied (source says which).
RegulationLimits apply_tolerances(RegulationLimits limits, const Tolerances& t);

}  // namespace meridian::gyro
