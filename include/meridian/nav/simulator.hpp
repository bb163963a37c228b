#pragma once
/// \file simulator.hpp
/// The validation scenario of shared/spec/navigation.md §8 (the 1988 experiment): a straight
/// survey line sampled every 5 s, range-range LOPs from two or three shore stations with
/// σ = 50 m and injected blunders, dead reckoning with one of four speed errors (I = sample
/// index, t = I·Δt):
///
///   A  bias         e(I) = 0.5 + 0.1·sin(π·I/6) m/s
///   B  no bias      e(I) = 0.1·sin(π·I/6)
///   C  bias change  0.5, 0.8 for 10 ≤ t/min < 15, then 0.5 again (plus the sine term)
///   D  bad start    case A, with the initial position 100 m off the truth
///
/// The speed error acts along the heading: the logged speed is v + e(I) (so the velocity bias
/// to estimate is W = −e·(cos α, sin α)). White errors σ_speed, σ_heading are added per sample
/// and reported in DrSample::covariance. Deterministic for a seed (std::mt19937_64 with
/// std::normal_distribution, so the same numbers with the same standard library).
#include <cstdint>
#include <string>

#include "meridian/nav/navigation.hpp"

namespace meridian::nav {

enum class Scenario { A, B, C, D };

/// "A" … "D" (either case). Throws InputError otherwise.
Scenario scenario_from_string(const std::string& name);
std::string to_string(Scenario s);

struct SimulationOptions {
  Scenario scenario = Scenario::A;
  std::uint64_t seed = 1;
  int stations = 3;               ///< 2 or 3 shore stations
  double duration_s = 1800.0;     ///< > 0 (30 min: scenario C's changes at 10 and 15 min)
  double step_s = 5.0;            ///< DR sampling (s), > 0
  double lop_interval_s = 0.0;    ///< LOP epochs every this many seconds (≥ 0); 0: every DR sample
  double speed_m_s = 5.0;         ///< true speed over ground (m/s), > 0
  double heading_rad = 1.0471975511965976;  ///< true course (60°), clockwise from north
  double sigma_range_m = 50.0;    ///< LOP σ (m), > 0
  double blunder_probability = 0.02;  ///< per LOP, in [0, 1)
  double blunder_min_m = 300.0;   ///< size of a blunder: uniform in [min, max] with random sign
  double blunder_max_m = 800.0;
  double sigma_speed_m_s = 0.02;  ///< white speed error (m/s), ≥ 0
  double sigma_heading_rad = 0.001;  ///< white heading error (rad), ≥ 0
  double fix_interval_s = 0.0;    ///< a satellite fix every this many seconds; 0: none
  double sigma_fix_m = 10.0;      ///< σ of each fix coordinate (m), > 0
};

struct SimulatedLine {
  Input input;                   ///< with truth at every DR epoch and default Options
  std::vector<std::size_t> blunders;  ///< indices into input.lops of the injected blunders
  std::string settings;          ///< one line naming every setting (for a `# ` comment)
};

/// Throws InputError (field "simulation.<name>") for an option out of range.
SimulatedLine simulate(const SimulationOptions& options);

}  // namespace meridian::nav
