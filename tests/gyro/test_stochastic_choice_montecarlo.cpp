// Monte Carlo of the recommendation of gyro stochastic (issue 31) with a simulator written
// here from the physics, not the product's: the turning points of a damped oscillation
// x(t) = M + A·e^{−δt}·cos(ωt) (dx/dt = 0 at ωt_k = kπ − φ, tan φ = δ/ω), read with white,
// stationary Markov-1, stationary Markov-2 or white + Markov-1 errors (burn-in, not the
// product's initial-state model). For n = 7, 15, 31 the recommended model's 95 % interval
// (t_{0.975}(n − 3)·m) must cover the true centre in ≥ 90 % of the runs and its rms error must
// not exceed white noise's by more than 10 %; a planted 2′ blunder must be located in ≥ 95 % of
// the runs at n ≥ 15. Label `montecarlo`.
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "meridian/gyro/stochastic.hpp"

namespace {

using namespace meridian::gyro;

constexpr double kTrueCentre = 754.0;  // arcsec (0°12′34″ relative to the reference)
constexpr double kAmplitude = 4800.0;  // arcsec
constexpr double kKappa = 0.002;       // decay per half period

enum class Noise { White, Markov1, Markov2, WhitePlusMarkov };

const char* name(Noise e) {
  switch (e) {
    case Noise::White:
      return "white";
    case Noise::Markov1:
      return "markov1";
    case Noise::Markov2:
      return "markov2";
    case Noise::WhitePlusMarkov:
      return "white+markov1";
  }
  return "?";
}

// Turning points of the damped oscillation (period 2π/ω = 2, so one half period = 1):
// ω = π, δ = κ (decay per half period), x_k = M + (−1)^k·A·cos φ·e^{−δ t_k}.
std::vector<double> turning_points(int n) {
  const double omega = M_PI, delta = kKappa;
  const double phi = std::atan(delta / omega);
  std::vector<double> x;
  for (int k = 1; k <= n; ++k) {
    const double t = (k * M_PI - phi) / omega;
    x.push_back(kTrueCentre + (k % 2 == 0 ? 1.0 : -1.0) * kAmplitude * std::cos(phi) *
                                  std::exp(-delta * t));
  }
  return x;
}

// Stationary coloured errors by running the recursion 50 steps before the first reading.
std::vector<double> errors(Noise e, int n, std::mt19937_64& rng) {
  std::normal_distribution<double> z(0.0, 1.0);
  const int burn = 50;
  std::vector<double> out;
  double e1 = 0.0, e2 = 0.0;
  for (int k = -burn; k < n; ++k) {
    double v = 0.0;
    switch (e) {
      case Noise::White:
        v = 6.0 * z(rng);
        break;
      case Noise::Markov1:
        v = 0.6 * e1 + 6.0 * z(rng);
        break;
      case Noise::Markov2:
        v = 0.5 * e1 + 0.25 * e2 + 5.0 * z(rng);
        break;
      case Noise::WhitePlusMarkov:
        v = 0.7 * e1 + 4.0 * z(rng);  // the Markov part; white reading noise added below
        break;
    }
    e2 = e1;
    e1 = v;
    if (k >= 0) out.push_back(e == Noise::WhitePlusMarkov ? v + 4.0 * z(rng) : v);
  }
  return out;
}

StochasticInput series(Noise e, int n, std::mt19937_64& rng, int blunder_at = 0) {
  StochasticInput in;
  in.kind = SeriesKind::Scale;  // fitted as given (arcsec here)
  in.readings = turning_points(n);
  const auto err = errors(e, n, rng);
  for (int i = 0; i < n; ++i) in.readings[static_cast<std::size_t>(i)] += err[static_cast<std::size_t>(i)];
  if (blunder_at > 0) in.readings[static_cast<std::size_t>(blunder_at - 1)] += 120.0;
  in.booked_sigma = 6.0;
  return in;
}

// The value a user takes: StochasticResult::answer.
struct Answer {
  double centre, sigma, half95;
};
Answer answer(const StochasticResult& r) { return {r.answer.value, r.answer.sigma, r.answer_half95}; }

struct Stats {
  int runs = 0, covered = 0, white_covered = 0, correlated = 0;
  double se_rec = 0.0, se_white = 0.0, var_rep = 0.0;
};

Stats run_case(Noise e, int n, int runs, unsigned seed) {
  std::mt19937_64 rng(seed);
  Stats s;
  const double tw = interval95_factor(n);
  for (int k = 0; k < runs; ++k) {
    const StochasticResult r = analyse_stochastic(series(e, n, rng));
    const Answer a = answer(r);
    const ModelFit& w = r.fit(StochasticModel::WhiteNoise);
    ++s.runs;
    s.covered += std::fabs(a.centre - kTrueCentre) <= a.half95 ? 1 : 0;
    s.white_covered += std::fabs(w.north.value - kTrueCentre) <= tw * w.north.sigma ? 1 : 0;
    s.correlated += r.models[static_cast<std::size_t>(r.recommended)].model != StochasticModel::WhiteNoise;
    s.se_rec += (a.centre - kTrueCentre) * (a.centre - kTrueCentre);
    s.var_rep += a.sigma * a.sigma;
    s.se_white += (w.north.value - kTrueCentre) * (w.north.value - kTrueCentre);
  }
  return s;
}

class Recommendation : public ::testing::TestWithParam<int> {};

TEST_P(Recommendation, CoversTheTruthAndIsNoWorseThanWhiteNoise) {
  const int n = GetParam();
  const int runs = n <= 7 ? 100 : (n <= 15 ? 60 : 30);
  for (Noise e : {Noise::White, Noise::Markov1, Noise::Markov2, Noise::WhitePlusMarkov}) {
    const Stats s = run_case(e, n, runs, 3100u + static_cast<unsigned>(n) * 10u + static_cast<unsigned>(e));
    const double cov = static_cast<double>(s.covered) / s.runs;
    const double rms = std::sqrt(s.se_rec / s.runs), rms_w = std::sqrt(s.se_white / s.runs);
    std::printf("n = %2d %-14s runs %d: coverage %.3f (white %.3f), rms %.2f (white %.2f), "
                "rms reported sigma %.2f, correlated recommended %d\n",
                n, name(e), s.runs, cov, static_cast<double>(s.white_covered) / s.runs, rms, rms_w,
                std::sqrt(s.var_rep / s.runs), s.correlated);
    EXPECT_GE(cov, 0.90) << name(e) << " n = " << n;
    EXPECT_LE(rms, 1.10 * rms_w) << name(e) << " n = " << n;
  }
}

INSTANTIATE_TEST_SUITE_P(Lengths, Recommendation, ::testing::Values(7, 15, 31));

TEST(Snooping, PlantedBlunderIsLocated) {
  for (int n : {15, 31})
    for (Noise e : {Noise::White, Noise::Markov1}) {
      std::mt19937_64 rng(4100u + static_cast<unsigned>(n));
      std::uniform_int_distribution<int> at(1, n);
      const int runs = 100;
      int located = 0;
      for (int k = 0; k < runs; ++k) {
        const int i = at(rng);
        StochasticInput in = series(e, n, rng, i);
        in.options.covariance_functions = false;  // snooping does not depend on them
        in.options.markov2 = false;
        const StochasticResult r = analyse_stochastic(in);
        located += !r.outliers.empty() && r.outliers.front().reading == i ? 1 : 0;
      }
      std::printf("n = %2d %-8s blunder 120 arcsec located in %d of %d\n", n, name(e), located, runs);
      EXPECT_GE(located, 95 * runs / 100) << name(e) << " n = " << n;
    }
}

}  // namespace
