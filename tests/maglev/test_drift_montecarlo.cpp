// Monte Carlo of the common drift (issue 30) with a simulator written here from the physics, not
// the product's: one clock for every block, the rotor current
//   I_k(t) = K·ω_ie·cos φ·cos β_k + b + d·t + u(t) + w(t),   β_k = α_k − 90°, α_2 = α_1 + 180°,
// u an AR(1) process running through the pauses between blocks (the instrument does not stop),
// w white noise. Label `montecarlo`.

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "meridian/maglev/reduce.hpp"

using namespace meridian;
using namespace meridian::maglev;

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kOmega = 7.292115e-5;  // rad/s
constexpr double kArcsec = kPi / 648000.0;

struct Geometry {
  const char* name;
  double K, latitude_deg, alpha1_deg, rate_hz;
  std::size_t block_samples;
  double pause_s, phi, innovation_A, white_A, bias_A;
};

// The trial's setting (K 6000, 34.25°, 10 Hz, 300 s per position, 40 s pause) and a second one:
// another latitude, α_1 far from north, a longer correlation, a faster rate.
const Geometry kTrial{"trial", 6000, 34.25, 0.866272865, 10, 3000, 40, 0.8, 3e-5, 3e-5, 3e-4};
const Geometry kNorth{"north", 8000, 52.0, -25.0, 20, 2500, 60, 0.9, 1e-5, 2e-5, -1e-4};

// Standard normal by Box–Muller on a 32-bit Mersenne twister (the product uses mt19937_64 and
// std::normal_distribution).
struct Normal {
  std::mt19937 rng;
  bool have = false;
  double spare = 0.0;
  explicit Normal(std::uint32_t seed) : rng(seed) {}
  double operator()() {
    if (have) {
      have = false;
      return spare;
    }
    const double u1 = (static_cast<double>(rng()) + 1.0) / 4294967297.0;
    const double u2 = static_cast<double>(rng()) / 4294967296.0;
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare = r * std::sin(2.0 * kPi * u2);
    have = true;
    return r * std::cos(2.0 * kPi * u2);
  }
};

// settling_A: after each rotation −settling_A·exp(−t/τ) at position 1, +settling_A·exp(…) at
// position 2 (the trial's case), τ = settling_tau_s, t from the block's first sample.
ReduceInput physics(const Geometry& g, double drift_A_per_s, const std::vector<int>& sequence,
                    std::uint32_t seed, double settling_A = 0.0, double settling_tau_s = 20.0) {
  Normal n(seed);
  const double phi = g.latitude_deg * kPi / 180.0;
  const double a1 = g.alpha1_deg * kPi / 180.0;
  ReduceInput in;
  in.scale_A_s_per_rad = {g.K, 0.0};
  in.latitude_rad = phi;
  in.circle_reading1_rad = {0.0, 0.0};
  const double dt = 1.0 / g.rate_hz;
  double u = n() * g.innovation_A / std::sqrt(1.0 - g.phi * g.phi);
  std::size_t tick = 0;
  const auto pause_ticks = static_cast<std::size_t>(std::llround(g.pause_s * g.rate_hz));
  for (std::size_t b = 0; b < sequence.size(); ++b) {
    const int k = sequence[b];
    const double beta = (k == 1 ? a1 : a1 + kPi) - kPi / 2.0;
    PositionSeries& s = k == 1 ? in.position1 : in.position2;
    for (std::size_t i = 0; i < g.block_samples; ++i, ++tick) {
      const double t = static_cast<double>(tick) * dt;
      u = g.phi * u + g.innovation_A * n();
      s.time_s.push_back(t);
      const double settle = (k == 1 ? -settling_A : settling_A) *
                            std::exp(-static_cast<double>(i) * dt / settling_tau_s);
      s.current_A.push_back(g.K * kOmega * std::cos(phi) * std::cos(beta) + g.bias_A +
                            drift_A_per_s * t + settle + u + g.white_A * n());
    }
    for (std::size_t i = 0; i < pause_ticks; ++i, ++tick) u = g.phi * u + g.innovation_A * n();
  }
  return in;
}

struct Summary {
  double mean_error = 0, rms = 0, mean_sigma = 0, max_abs_z = 0, mean_inflation = 0;
  int runs = 0, not_separable = 0, drift_flagged = 0;
  double se() const { return rms / std::sqrt(static_cast<double>(runs)); }
};

Summary monte_carlo(const Geometry& g, double drift, const std::vector<int>& sequence, int runs,
                    std::uint32_t seed0, DriftModel model = DriftModel::linear,
                    double settling_A = 0.0, int* blocks_cut = nullptr) {
  Summary s;
  s.runs = runs;
  const double truth = g.alpha1_deg * kPi / 180.0;
  for (int k = 0; k < runs; ++k) {
    ReduceInput in =
        physics(g, drift, sequence, seed0 + static_cast<std::uint32_t>(k), settling_A);
    in.options.drift = model;
    // Without the drift model the drift within each block is a ramp that the settling test may
    // take for a slow transient, and cuts of unequal length break the symmetry that cancels the
    // drift (docs: use --no-settling-detect with --drift none).
    in.options.settling.detect = model != DriftModel::none;
    const ReduceResult r = process(in);
    if (blocks_cut) *blocks_cut += static_cast<int>(r.settling.size());
    const double e = r.processed.alpha1_rad.value - truth;
    s.mean_error += e / runs;
    s.rms += e * e / runs;
    s.mean_sigma += r.processed.alpha1_rad.sigma / runs;
    s.max_abs_z = std::max(s.max_abs_z, std::abs(e / r.processed.alpha1_rad.sigma));
    if (r.drift) {
      s.mean_inflation += r.drift->sigma_inflation / runs;
      s.not_separable += r.drift->separable ? 0 : 1;
      s.drift_flagged += r.drift->significant ? 1 : 0;
    }
  }
  s.rms = std::sqrt(s.rms);
  if (std::getenv("MERIDIAN_MC_VERBOSE"))
    std::printf("%-5s drift %.0e seq %zu blocks: mean err %+.3f\" (SE %.3f\")  rms %.3f\"  "
                "mean sigma %.3f\"  max|z| %.2f  inflation %.2f  drift significant %d/%d\n",
                g.name, drift, sequence.size(), s.mean_error / kArcsec, s.se() / kArcsec,
                s.rms / kArcsec, s.mean_sigma / kArcsec, s.max_abs_z, s.mean_inflation,
                s.drift_flagged, runs);
  return s;
}
}  // namespace

// One 1-2 determination per seed, 40 seeds for each drift (0, 2e-8, 2e-7 A/s) and geometry:
// α_1 unbiased within 3 standard errors; the reported σ against the RMS error, per drift within
// ±30 % (the RMS of 40 errors is itself known to ±11 %) and pooled over the 120 runs of a
// geometry within ±20 % (±6.5 %).
TEST(DriftMonteCarlo, ContinuousDriftLeavesAlphaUnbiasedWithHonestSigma) {
  for (const Geometry* g : {&kTrial, &kNorth}) {
    double pooled_ms = 0, pooled_sigma = 0;
    std::uint32_t seed = 100;
    for (double drift : {0.0, 2e-8, 2e-7}) {
      const Summary s = monte_carlo(*g, drift, {1, 2}, 40, seed);
      seed += 1000;
      EXPECT_LT(std::abs(s.mean_error), 3.0 * s.se()) << g->name << " drift " << drift;
      EXPECT_NEAR(s.mean_sigma / s.rms, 1.0, 0.3) << g->name << " drift " << drift;
      EXPECT_EQ(s.not_separable, 0) << g->name;
      // One block per position: the drift costs σ, at least ×2 (VIF ≥ 4).
      EXPECT_GT(s.mean_inflation, 2.0) << g->name;
      pooled_ms += s.rms * s.rms / 3.0;
      pooled_sigma += s.mean_sigma / 3.0;
      if (drift == 2e-7) {
        EXPECT_GE(s.drift_flagged, 36) << g->name << ": 2e-7 A/s is ~9σ";
      }
    }
    EXPECT_NEAR(pooled_sigma / std::sqrt(pooled_ms), 1.0, 0.2) << g->name;
  }
}

// Without the drift model, 1-2 is biased by the drift (the trial's finding, the reason for the
// model), while the symmetric sequences 1-2-1 and 1-2-2-1 cancel it by design (unbiased; their
// per-position σ then holds the drift's spread and is conservative); with the model they stay
// unbiased, the σ matches the scatter (60 seeds: ±9 %) and the drift hardly costs σ.
TEST(DriftMonteCarlo, SymmetricSequencesCancelTheDrift) {
  const Summary biased = monte_carlo(kTrial, 2e-7, {1, 2}, 10, 7000, DriftModel::none);
  EXPECT_GT(std::abs(biased.mean_error), 5.0 * biased.mean_sigma);  // about −19″ with σ 3″
  for (const std::vector<int>& seq : {std::vector<int>{1, 2, 1}, std::vector<int>{1, 2, 2, 1}}) {
    const Summary none = monte_carlo(kTrial, 2e-7, seq, 20, 8000, DriftModel::none);
    EXPECT_LT(std::abs(none.mean_error), 3.0 * none.se()) << seq.size() << " blocks";
    EXPECT_GT(none.mean_sigma, 0.8 * none.rms) << seq.size() << " blocks";
    const Summary s = monte_carlo(kTrial, 2e-7, seq, 60, 9000, DriftModel::linear);
    EXPECT_LT(std::abs(s.mean_error), 3.0 * s.se()) << seq.size() << " blocks";
    EXPECT_NEAR(s.mean_sigma / s.rms, 1.0, 0.25) << seq.size() << " blocks";
    EXPECT_LT(s.mean_inflation, 1.3) << seq.size() << " blocks";
  }
}

// Settling transients of ∓3e-4 A (τ 20 s) after each rotation, with a drift of 2e-8 A/s: detected
// and cut in every block, α_1 unbiased within 3 standard errors and σ within ±30 % of the RMS
// error over 30 seeds (the trial: −4.1″ ± 0.6″ over 15 seeds while σ said 2.5″).
TEST(DriftMonteCarlo, SettlingIsCutWithoutBias) {
  int cut = 0;
  const Summary s = monte_carlo(kTrial, 2e-8, {1, 2}, 30, 12000, DriftModel::linear, 3e-4, &cut);
  EXPECT_EQ(cut, 60);
  EXPECT_LT(std::abs(s.mean_error), 3.0 * s.se());
  EXPECT_NEAR(s.mean_sigma / s.rms, 1.0, 0.3);
}

// The performance target: 2 × 3000 samples with the drift model (tests, denoising) in < 50 ms.
TEST(DriftMonteCarlo, TwoPositionsOf3000SamplesWithTheDriftModelTakeUnder50ms) {
  const ReduceInput in = physics(kTrial, 2e-7, {1, 2}, 1);
  process(in);  // warm-up
  const auto t0 = std::chrono::steady_clock::now();
  const int reps = 5;
  for (int k = 0; k < reps; ++k) process(in);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() /
      reps;
  std::printf("2 x 3000 samples with the drift model: %.2f ms per determination\n", ms);
#ifdef NDEBUG
  EXPECT_LT(ms, 50.0);
#endif
}
