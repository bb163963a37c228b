#include "meridian/gravity/synthetic.hpp"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::gravity {
namespace {

// SplitMix64 (Steele, Lea & Flood 2014): the same stream on every platform,
// unlike std::normal_distribution.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : s_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (s_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double uniform() { return (static_cast<double>(next() >> 11) + 0.5) * 0x1.0p-53; }  // (0, 1)
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double r = std::sqrt(-2 * std::log(uniform())), a = 2 * std::numbers::pi * uniform();
    spare_ = r * std::sin(a);
    has_spare_ = true;
    return r * std::cos(a);
  }

 private:
  std::uint64_t s_;
  double spare_ = 0;
  bool has_spare_ = false;
};

}  // namespace

GravityModelData make_synthetic_model(const SyntheticModelOptions& o) {
  if (o.max_degree < 2 || o.max_degree > 2190)
    throw InputError(fmt::format("synthetic model degree {} is outside [2, 2190]", o.max_degree), {"", {}, "degree"});
  if (!(o.kaula_scale > 0 && std::isfinite(o.kaula_scale)))
    throw InputError("Kaula scale must be positive", {"", {}, "kaula_scale"});
  GravityModelData m;
  m.name = fmt::format("synth{}s{}", o.max_degree, o.seed);
  m.description = fmt::format("Meridian synthetic model, Kaula {:g}/n^2, degree {}, seed {}", o.kaula_scale, o.max_degree, o.seed);
  m.tide_system = "tide_free";
  m.normalization = "fully_normalized";
  m.gm_m3_s2 = 3.986004415e14;
  m.radius_m = 6378136.3;
  m.file_max_degree = o.max_degree;
  m.coefficients = SphericalHarmonicCoefficients(o.max_degree, o.max_degree);
  Rng rng(o.seed);
  m.coefficients.set(0, 0, 1.0, 0.0);
  for (int n = 2; n <= o.max_degree; ++n) {
    const double sigma = o.kaula_scale / (static_cast<double>(n) * n);
    for (int k = 0; k <= n; ++k) {
      const double c = sigma * rng.normal(), s = sigma * rng.normal();
      m.coefficients.set(n, k, c, k == 0 ? 0.0 : s);
    }
  }
  // An Earth-like flattening term, so removing the normal field matters.
  m.coefficients.set(2, 0, -4.841653e-4 + m.coefficients.c(2, 0), 0.0);
  return m;
}

}  // namespace meridian::gravity
