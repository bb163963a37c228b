#pragma once
/// \file instrument_spec.hpp
/// An instrument as described in a file (constants possibly determined at
/// another latitude, or given as periods) and its resolution to the
/// Instrument constants at a station latitude.

#include <optional>
#include <string>
#include <vector>

#include "meridian/gyro/constants.hpp"
#include "meridian/gyro/instrument.hpp"

namespace meridian::gyro {

struct InstrumentSpec {
  std::string name;
  std::string serial;                          ///< serial number (record sheet only)
  double scale_value_rad = 0.0;                ///< τ (rad/div), > 0
  double sigma_scale_value_rad = 0.0;
  /// λ given directly, with σ. Mutually exclusive with the periods.
  std::optional<Uncertain> torsion_ratio;
  /// Latitude φ0 at which λ or the periods were determined (radians). When
  /// absent they are taken to hold at the station latitude.
  std::optional<double> constants_latitude_rad;
  std::optional<Uncertain> tracking_period_s;     ///< T_A
  std::optional<Uncertain> nontracking_period_s;  ///< T_B (with T_A gives λ = (T_A/T_B)² − 1)
  std::optional<Uncertain> free_period_s;         ///< T_F (with T_A gives λ = (T_A/T_F)²)
  /// Calibrated transit factor c (rad/(div·s)) valid at constants_latitude.
  std::optional<Uncertain> transit_factor_rad_per_div_s;
  double sigma_time_s = kDefaultSigmaTime_s;
  double sigma_reading_div = kDefaultSigmaReading_div;
  double latitude_limit_rad = kDefaultLatitudeLimit_rad;
  /// Nominal accuracy class (arcsec), e.g. 5, 15 or 25: sets the limits of
  /// the checks (regulations.hpp).
  double accuracy_class_arcsec = kDefaultAccuracyClass_arcsec;
  /// accuracy_class_arcsec was booked (a file without `accuracy_class_arcsec` sets false: the
  /// campaign then takes the class from the instrument's name, else the 15″ default, and
  /// fails the check "accuracy class booked"). Code that builds an Input states its class.
  bool accuracy_class_booked = true;
};

/// The accuracy class (arcsec) an instrument's name states, for the names of the
/// tape-suspended gyro-theodolites of the coal-mine surveying regulations: "JT<n>" (also
/// "JT-<n>", "JT <n>", any case) is an n″ instrument (JT15 → 15, JT5 → 5); "GAK1" is a
/// 15″ instrument (spec §7.1). Anything else: std::nullopt (no class is guessed).
std::optional<double> accuracy_class_from_name(const std::string& name);

/// Instrument constants at `station_lat_rad`, plus what was done to get them.
struct ResolvedInstrument {
  Instrument instrument;
  std::vector<std::string> notes;   ///< e.g. "lambda rescaled from 34.0° to 36.5°"
};

/// Resolve λ (given, or from periods) and rescale it to the station
/// latitude by λ(φ) = λ(φ0)·cos φ0/cos φ; a calibrated c is rescaled with
/// it (rescale_transit_factor in constants.hpp). A note records each
/// rescaling that changes the printed value (λ to 5 decimals, c to
/// 0.0001″/(div·s)). Throws InputError when
/// neither λ nor usable periods are given, when both are, or when the
/// latitude is beyond the limit.
ResolvedInstrument resolve_instrument(const InstrumentSpec& spec, double station_lat_rad);


}  // namespace meridian::gyro
