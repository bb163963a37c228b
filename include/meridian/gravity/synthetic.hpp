#pragma once
/// \file synthetic.hpp
/// Random gravity models for tests, benchmarks and examples that must not
/// depend on files that cannot be shipped.

#include <cstdint>
#include <string>

#include "meridian/gravity/gravity_model.hpp"

namespace meridian::gravity {

struct SyntheticModelOptions {
  int max_degree = 360;          ///< N, 2 ≤ N ≤ 2190
  std::uint64_t seed = 1;        ///< same seed → same coefficients on every platform
  double kaula_scale = 1e-5;     ///< Kaula's rule: rms of C̄_nm, S̄_nm = kaula_scale / n²
};

/// A model with GM = 3.986004415e14 m³/s², a = 6378136.3 m (as EGM96 and
/// EGM2008), C̄00 = 1, no degree-1 terms, C̄20 = −4.841653e-4 plus noise, and
/// for n ≥ 2 independent Gaussian C̄_nm, S̄_nm with σ = kaula_scale/n²
/// (portable generator: SplitMix64 + Box–Muller). Reference field WGS84.
GravityModelData make_synthetic_model(const SyntheticModelOptions& options);

/// `gravity synth-model`: a synthetic model and the files it was written to (the Result of
/// io::write_synthetic_model, for report::synthetic_model_text).
struct SyntheticModelFiles {
  std::string prefix;             ///< the files are PREFIX.gfc, PREFIX.egm and PREFIX.egm.cof
  std::string model_name;         ///< GravityModelData::name
  SyntheticModelOptions options;  ///< as used
};

}  // namespace meridian::gravity
