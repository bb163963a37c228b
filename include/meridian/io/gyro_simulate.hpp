#pragma once
/// \file gyro_simulate.hpp
/// `meridian gyro simulate`: its settings as a user types them, read into what to simulate
/// (a station's runs, gyro::simulate_station, or the example campaign, gyro::simulate_campaign),
/// and the runner that simulates the field book. The book's text is written by
/// simulated_book_yaml (io/gyro_writers.hpp). docs/gyro-simulator.md.
///
///   SimulateSettings (CLI options) → read_simulate_settings → SimulationInput
///   → run_simulation → SimulatedBook → simulated_book_yaml

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "meridian/core/progress.hpp"
#include "meridian/gyro/campaign_simulator.hpp"
#include "meridian/gyro/station_simulator.hpp"

namespace meridian::io {

/// The settings of `meridian gyro simulate` as typed: the CLI binds its options to these members
/// (their defaults are the options' defaults). Members of `sim` that are given in their own unit
/// (div, s, counts, ρ, λ) are set directly; angles, the scale value and the noise model are here
/// as typed, and read_simulate_settings converts them.
struct SimulateSettings {
  std::string mode = "non-tracking";  ///< non-tracking | tracking | campaign
  std::uint64_t seed = 1;
  gyro::StationSimulation sim;
  double tau_arcsec = 600, latitude_deg = 34.2;
  /// H, J_z, D_B: when any is > 0 the periods and λ follow from the physics (gyro::PhysicalGyro).
  double spin_momentum_Nms = 0, inertia_kgm2 = 0, torsion_Nm_per_rad = 0;
  std::vector<std::string> clamps{"0"};  ///< N′ of the determinations in turn (DMS or degrees)
  std::string centre = "0 12 34";        ///< tracking: M (DMS or degrees)
  std::string noise = "white";           ///< white | markov1 | markov2
  double sigma_tracking_arcsec = 0;
  std::optional<double> sigma_initial_arcsec;  ///< σ_2 of Markov tracking noise; default σ_1
  /// Long names of the options the user gave ("levels", "kappa"): one that the mode does not use
  /// is refused, not silently dropped.
  std::vector<std::string> given;
  /// The command line as it can be typed again (for the simulated book's header).
  std::string command_line;
};

/// What to simulate, as plain data.
struct SimulationInput {
  std::uint64_t seed = 1;
  /// One station's runs (non-tracking or tracking), or a campaign from its truth.
  std::variant<gyro::StationSimulation, gyro::CampaignTruth> what;
  std::string command_line;  ///< SimulateSettings::command_line
};

/// Check the settings against the mode and convert them: angles parsed (core/dms.hpp), arcsec and
/// degrees to radians, the noise model named. The campaign mode simulates the example campaign's
/// set-up (gyro::example_campaign_truth) with the given seed and white timing and reading σ only.
/// Throws InputError (ParseError for an angle) at the option's field ("--clamp", "--noise") for
/// an unknown mode or noise model, an option the mode does not use, a clamp list that does not
/// fit the determinations, or an initial-state σ without Markov tracking noise or below 0.
SimulationInput read_simulate_settings(const SimulateSettings& settings);

/// A simulated field book: a station's reduce book or a campaign, with its truth.
struct SimulatedBook {
  std::variant<gyro::SimulatedStation, gyro::SimulatedCampaign> book;
  std::string command_line;  ///< what made it (SimulationInput::command_line)
};

/// Simulate what `in` says (deterministic for its seed). Throws the simulators' InputError for
/// invalid parameters.
SimulatedBook run_simulation(const SimulationInput& in, Progress* progress = nullptr);

/// read_simulate_settings, then run_simulation.
SimulatedBook run_simulation(const SimulateSettings& settings, Progress* progress = nullptr);

}  // namespace meridian::io
