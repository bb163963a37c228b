#pragma once
/// \file dov_writers.hpp
/// Writers of the deflection-of-the-vertical workflow's input files (`dov simulate`,
/// `dov convert`): the line CSV of dov_files.hpp and the configuration that names a simulated
/// line. The binary line's writer is dov_binary.hpp.

#include <string>
#include <vector>

#include "meridian/dov/deflection.hpp"

namespace meridian::io {

/// The line CSV of `input` (the columns of dov_files.hpp, truth columns when input.truth is not
/// empty, every number with 17 significant digits so that a read gives the same doubles back).
/// `settings`, when not empty, is written as a `# ` comment line before the header (the
/// simulator's settings; the reader skips comments).
std::string dov_line_csv(const dov::Input& input, const std::string& settings = {});

/// The comment and header lines of a line CSV as dov_line_csv writes them; `model`: the
/// model_eta_arcsec, model_xi_arcsec columns, `truth`: truth_eta_arcsec, truth_xi_arcsec.
std::string dov_line_csv_header(bool model, bool truth, const std::string& settings = {});
/// Append the rows of samples[k] (and truth[k] when `truth`; truth.size() == samples.size()
/// then) under a dov_line_csv_header(model, truth), 17 significant digits.
void append_dov_line_csv_rows(std::string& out, const std::vector<dov::Sample>& samples,
                              const std::vector<dov::Truth>& truth, bool model, bool truth_columns);

/// A configuration for processing a simulated line (`dov simulate --config`), with the
/// processing options that match the simulation. The values are in the configuration's units
/// as the user gave them (arc-seconds), so the numbers written are those typed.
struct DovSimulationConfig {
  std::string config_path;  ///< where the configuration is written
  std::string line_path;    ///< where the line is written; named relative to config_path's folder
  double sigma_model_arcsec = 3.0;  ///< the simulated model error: sigma_model_arcsec
  double sigma_ins_arcsec = 0.5;    ///< the simulated INS noise: sigma_obs_arcsec (0: the spec's 0.5)
  bool transport_rate = false;      ///< simulated with the transport rate: transport_rate: true
};

/// The YAML text of that configuration (docs/deflection.md, "Configuration"):
///
///   # meridian dov process configuration (spec defaults)
///   line: <line_path relative to the configuration's folder>
///   sigma_model_arcsec: …
///   sigma_obs_arcsec: …
///   transport_rate: true            # only when simulated so
std::string dov_simulation_config_yaml(const DovSimulationConfig& config);

}  // namespace meridian::io
