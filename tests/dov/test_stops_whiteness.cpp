// Issue 33 (stops and whiteness): stops with noisy GNSS speed, the reference speed of P₀ on a
// line that starts at rest, and the Ljung–Box whiteness test of the normalised innovations.
//
// The lines come from an INDEPENDENT simulator written here from the physics, not from
// src/dov/simulator.cpp: the deflection is a field over the ground, so its short-wavelength
// part is a second-order Gauss–Markov process in the distance travelled (wavelength λ = 10 km,
// ζ = 0.05, σ = 3″) — a carrier that stands still sees a constant deflection, one that moves
// at V sees the time process of model.hpp with ω₀ = 2πV/λ; the LGU/GNSS attitude error
// integrates φ̇ = −Ω×φ − ε_U·e_U by Runge–Kutta 4; the plumb-line frame n′ is the shortest
// rotation (Eigen's FromTwoVectors) from the ellipsoid normal to (η, ξ, 1)/norm; the GNSS
// speed over ground is the norm of the horizontal velocity plus white noise per component;
// the INS/GNSS attitude noise is white or first-order Gauss–Markov. The numbers each test
// measured are printed for docs/deflection.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "dov_test_support.hpp"
#include "meridian/dov/deflection.hpp"
#include "meridian/filter/whiteness.hpp"
#include "meridian/report/dov_outputs.hpp"

namespace {

using namespace meridian::dov;
namespace units = meridian::units;
using meridian_test::kAs;

/// A piecewise-linear true speed profile: (time s, speed m/s) knots.
using Profile = std::vector<std::pair<double, double>>;

double speed_at(const Profile& p, double t) {
  if (t <= p.front().first) return p.front().second;
  for (std::size_t i = 1; i < p.size(); ++i)
    if (t <= p[i].first) {
      const double f = (t - p[i - 1].first) / (p[i].first - p[i - 1].first);
      return p[i - 1].second + f * (p[i].second - p[i - 1].second);
    }
  return p.back().second;
}

struct Line {
  Profile speed;                          // true speed profile
  double duration_s = 600.0;              // 1 Hz
  double speed_sigma_m_s = 0.0;           // GNSS velocity noise per horizontal component
  double ins_sigma_rad = 0.5 * kAs;       // INS/GNSS attitude noise (each axis)
  double ins_tau_s = 0.0;                 // 0: white; else first-order Gauss–Markov
  std::uint64_t seed = 1;
};

struct Simulated {
  Input input;
  std::vector<double> true_speed;
};

/// A 2×2 Gauss–Markov step over `ds` metres of track: (u, δ) with u' = δ,
/// δ' = −ω²u − 2ζωδ + w (ω = 2π/λ per metre); closed form of the damped oscillator and
/// Q = P∞ − ΦP∞Φᵀ. ds = 0: nothing changes.
Eigen::Vector2d field_step(const Eigen::Vector2d& x, double ds, std::mt19937_64& rng) {
  if (ds <= 0.0) return x;
  constexpr double kZeta = 0.05, kSigma = 3.0 * kAs;
  const double w = 2.0 * units::kPi / 10000.0;
  const double a = kZeta * w, wd = w * std::sqrt(1.0 - kZeta * kZeta);
  const double e = std::exp(-a * ds), c = std::cos(wd * ds), s = std::sin(wd * ds);
  Eigen::Matrix2d phi;
  phi << e * (c + a / wd * s), e * s / wd, -e * w * w / wd * s, e * (c - a / wd * s);
  const Eigen::Matrix2d p = Eigen::Vector2d(kSigma / w, kSigma).cwiseAbs2().asDiagonal();
  const Eigen::Matrix2d q = p - phi * p * phi.transpose();
  const Eigen::Matrix2d l = q.llt().matrixL();
  std::normal_distribution<double> nd;
  return phi * x + l * Eigen::Vector2d(nd(rng), nd(rng));
}

Eigen::Matrix3d small_rotation(const Eigen::Vector3d& a) {  // exp(−[a×])
  const double n = a.norm();
  if (n == 0.0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(-n, a / n).toRotationMatrix();
}

Simulated simulate_line(const Line& line) {
  std::mt19937_64 rng(line.seed * 7919 + 17);
  std::normal_distribution<double> nd;
  constexpr double kR = 6371000.0, kWie = 7.292115e-5;
  const double heading = 60.0 * units::kDegree;
  const double eps_u = nd(rng) * 0.003 * units::kDegree / 3600.0;  // drawn from P₀
  Eigen::Vector3d phi(nd(rng) * 2.0 * kAs, nd(rng) * 2.0 * kAs, nd(rng) * 5.0 * kAs);
  const double w = 2.0 * units::kPi / 10000.0;
  Eigen::Vector2d east(nd(rng) * 3.0 * kAs / w, nd(rng) * 3.0 * kAs);
  Eigen::Vector2d north(nd(rng) * 3.0 * kAs / w, nd(rng) * 3.0 * kAs);
  Eigen::Vector3d v_ins(nd(rng), nd(rng), nd(rng));
  v_ins *= line.ins_sigma_rad;
  double lat = 30.0 * units::kDegree, lon = 114.0 * units::kDegree, dist = 0.0;
  Simulated out;
  const auto rate = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d omega(0.0, kWie * std::cos(lat), kWie * std::sin(lat));
    return Eigen::Vector3d(-omega.cross(p) - Eigen::Vector3d(0.0, 0.0, eps_u));
  };
  const int n = static_cast<int>(line.duration_s) + 1;
  const double a_ins = line.ins_tau_s > 0.0 ? std::exp(-1.0 / line.ins_tau_s) : 0.0;
  const Eigen::Matrix3d body =
      (Eigen::AngleAxisd(-heading, Eigen::Vector3d::UnitZ()) *
       Eigen::AngleAxisd(1.0 * units::kDegree, Eigen::Vector3d::UnitX()) *
       Eigen::AngleAxisd(2.0 * units::kDegree, Eigen::Vector3d::UnitY()))
          .toRotationMatrix();
  for (int k = 0; k < n; ++k) {
    const double t = k;
    const double v = speed_at(line.speed, t);
    if (k > 0) {
      const double ds = 0.5 * (speed_at(line.speed, t - 1.0) + v);  // Δt = 1 s
      east = field_step(east, ds, rng);
      north = field_step(north, ds, rng);
      const Eigen::Vector3d k1 = rate(phi), k2 = rate(phi + 0.5 * k1), k3 = rate(phi + 0.5 * k2),
                            k4 = rate(phi + k3);
      phi += (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0;
      lat += ds * std::cos(heading) / kR;
      lon += ds * std::sin(heading) / (kR * std::cos(lat));
      dist += ds;
      for (int i = 0; i < 3; ++i)
        v_ins(i) = a_ins * v_ins(i) + std::sqrt(1.0 - a_ins * a_ins) * line.ins_sigma_rad * nd(rng);
    }
    const double eta_g = 4.0 * kAs * std::sin(dist / 40000.0);
    const double xi_g = 3.0 * kAs * std::cos(dist / 60000.0);
    const double eta = eta_g + east(1), xi = xi_g + north(1);
    const Eigen::Matrix3d nprime_to_n =
        Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(),
                                           Eigen::Vector3d(eta, xi, 1.0).normalized())
            .toRotationMatrix();
    Sample s;
    s.time_s = t;
    s.lat_rad = lat;
    s.lon_rad = lon;
    const double ve = v * std::sin(heading) + line.speed_sigma_m_s * nd(rng);
    const double vn = v * std::cos(heading) + line.speed_sigma_m_s * nd(rng);
    s.speed_m_s = std::hypot(ve, vn);
    s.lgu_body_to_nav = small_rotation(phi) * body;
    s.ins_body_to_nav = small_rotation(v_ins) * nprime_to_n.transpose() * body;
    s.model_eta_rad = eta_g;
    s.model_xi_rad = xi_g;
    out.input.samples.push_back(s);
    out.input.truth.push_back(Truth{eta, xi, std::nullopt});
    out.true_speed.push_back(v);
  }
  return out;
}

bool has(const std::vector<std::string>& v, const std::string& what) {
  return std::any_of(v.begin(), v.end(),
                     [&](const std::string& s) { return s.find(what) != std::string::npos; });
}

// ---------------------------------------------------------------------------------------------
// Stops.

/// Mean (error/σ)² of the smoothed η and ξ over the epochs where the carrier really stands.
struct StopStats {
  double z2_eta = 0.0, z2_xi = 0.0, rms_eta = 0.0, rms_xi = 0.0, sigma_eta = 0.0, sigma_xi = 0.0;
};
StopStats stop_stats(const Simulated& sim, const Result& r) {
  StopStats st;
  int n = 0;
  for (std::size_t k = 0; k < r.epochs.size(); ++k) {
    if (sim.true_speed[k] != 0.0) continue;
    const EpochResult& e = r.epochs[k];
    const double de = e.smoothed.eta_rad - sim.input.truth[k].eta_rad;
    const double dx = e.smoothed.xi_rad - sim.input.truth[k].xi_rad;
    st.z2_eta += de * de / (e.smoothed.sigma_eta_rad * e.smoothed.sigma_eta_rad);
    st.z2_xi += dx * dx / (e.smoothed.sigma_xi_rad * e.smoothed.sigma_xi_rad);
    st.rms_eta += de * de;
    st.rms_xi += dx * dx;
    st.sigma_eta += e.smoothed.sigma_eta_rad * e.smoothed.sigma_eta_rad;
    st.sigma_xi += e.smoothed.sigma_xi_rad * e.smoothed.sigma_xi_rad;
    ++n;
  }
  st.z2_eta /= n;
  st.z2_xi /= n;
  st.rms_eta = std::sqrt(st.rms_eta / n) / kAs;
  st.rms_xi = std::sqrt(st.rms_xi / n) / kAs;
  st.sigma_eta = std::sqrt(st.sigma_eta / n) / kAs;
  st.sigma_xi = std::sqrt(st.sigma_xi / n) / kAs;
  return st;
}

// 20 min at 5 m/s, a 20-s stop ramp, 20 min standing still, a 20-s start ramp, 20 min at
// 5 m/s; GNSS speed noise 3 cm/s per component. With the default options the stop is classed
// stationary throughout (its steps up to the 5-s hysteresis) and the smoothed η, ξ over the
// stop are consistent with their σ: mean z² over 12 seeds near 1. The old behaviour (0.01 m/s,
// no hysteresis) fails the same check.
TEST(DovStops, TwentyMinuteStopWithNoisySpeedIsConsistent) {
  Line line;
  line.duration_s = 3640.0;
  line.speed = {{0, 5}, {1200, 5}, {1220, 0}, {2420, 0}, {2440, 5}, {3640, 5}};
  line.speed_sigma_m_s = 0.03;
  // DOV_STOP_SEEDS=60 for a longer measurement (docs/deflection.md quotes 12 and 60)
  const int kSeeds = std::getenv("DOV_STOP_SEEDS") ? std::atoi(std::getenv("DOV_STOP_SEEDS")) : 12;
  constexpr int kOldSeeds = 4;
  double z2_new = 0.0, z2_old = 0.0, z2_new_eta = 0.0, z2_old_eta = 0.0;
  StopStats mean_new, mean_old;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    line.seed = static_cast<std::uint64_t>(seed);
    Simulated sim = simulate_line(line);
    const Result r = process(sim.input);
    const StopStats a = stop_stats(sim, r);
    // the 1200 standing steps (1201 samples at V = 0) are classed stationary after 5 s
    EXPECT_GE(r.summary.stationary_steps, 1190u) << "seed " << seed;
    EXPECT_LE(r.summary.stationary_steps, 1220u) << "seed " << seed;
    EXPECT_DOUBLE_EQ(r.summary.stationary_speed_m_s, 0.1);
    // the old behaviour (0.01 m/s, no hysteresis) on the first kOldSeeds seeds only (CI time)
    StopStats b;
    if (seed <= kOldSeeds) {
      Input old_in = sim.input;
      old_in.options.model.stationary_speed_m_s = 0.01;
      old_in.options.stationary_min_duration_s = 0.0;
      b = stop_stats(sim, process(old_in));
    }
    z2_new += a.z2_eta + a.z2_xi;
    z2_old += b.z2_eta + b.z2_xi;
    z2_new_eta += a.z2_eta;
    z2_old_eta += b.z2_eta;
    mean_new.rms_eta += a.rms_eta * a.rms_eta / kSeeds;
    mean_new.sigma_eta += a.sigma_eta * a.sigma_eta / kSeeds;
    mean_old.rms_eta += b.rms_eta * b.rms_eta / kOldSeeds;
    mean_old.sigma_eta += b.sigma_eta * b.sigma_eta / kOldSeeds;
    std::printf("  seed %2d: stop z² η %.2f ξ %.2f (0.1 m/s) | %.2f %.2f (0.01 m/s); "
                "stationary steps %zu, discretisations %zu\n",
                seed, a.z2_eta, a.z2_xi, b.z2_eta, b.z2_xi, r.summary.stationary_steps,
                r.summary.discretisations);
  }
  z2_new /= 2 * kSeeds;
  z2_old /= 2 * kOldSeeds;
  z2_new_eta /= kSeeds;
  z2_old_eta /= kOldSeeds;
  std::printf("20-min stop, 3 cm/s speed noise, %d seeds: mean z² (η, ξ pooled) %.3f, η %.3f; "
              "RMS η error %.3f″ against σ %.3f″ | old default 0.01 m/s (seeds 1-4): z² %.3f, η %.3f; RMS η "
              "%.3f″ against σ %.3f″\n",
              kSeeds, z2_new, z2_new_eta, std::sqrt(mean_new.rms_eta),
              std::sqrt(mean_new.sigma_eta), z2_old, z2_old_eta, std::sqrt(mean_old.rms_eta),
              std::sqrt(mean_old.sigma_eta));
  // 24 values of a z² that is about one χ²(1) per seed and component (the stop's errors are
  // one constant): 95 % of the means of 24 χ²(1) lie in [0.50, 1.61]
  EXPECT_GT(z2_new, 0.4);
  EXPECT_LT(z2_new, 1.7);
  EXPECT_LT(z2_new_eta, 2.0);
  EXPECT_GT(z2_old_eta, 2.0);  // the check can fail: the old threshold is optimistic
}

// A line that starts at rest (10 min standing, noisy speed), accelerates over 60 s and goes on
// at 5 m/s: P₀'s σ(x) is taken at the reference speed — the median speed at or above the
// threshold over the first 300 s of motion, motion beginning with the first run of ≥ 5 s at or
// above it — not at the first sample that crossed the threshold.
TEST(DovStops, LineStartingAtRestTakesP0AtTheReferenceSpeed) {
  Line line;
  line.duration_s = 1800.0;
  line.speed = {{0, 0}, {600, 0}, {660, 5}, {1800, 5}};
  line.speed_sigma_m_s = 0.03;
  line.seed = 3;
  const Simulated sim = simulate_line(line);
  const Result r = process(sim.input);
  // the rule, computed here from the samples
  const auto& s = sim.input.samples;
  std::size_t start = 0;
  for (std::size_t k = 0, run = 0; k < s.size(); ++k) {
    if (s[k].speed_m_s < 0.1) {
      run = k + 1;
      continue;
    }
    if (s[k].time_s - s[run].time_s >= 5.0) {
      start = run;
      break;
    }
  }
  std::vector<double> v;
  for (std::size_t k = start; k < s.size() && s[k].time_s - s[start].time_s <= 300.0; ++k)
    if (s[k].speed_m_s >= 0.1) v.push_back(s[k].speed_m_s);
  std::sort(v.begin(), v.end());
  const double median =
      v.size() % 2 == 1 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
  double first_crossing = 0.0;
  for (const Sample& x : s)
    if (x.speed_m_s >= 0.1) {
      first_crossing = x.speed_m_s;
      break;
    }
  std::printf("start at rest: motion from t = %.0f s, reference speed %.4f m/s (rule %.4f), "
              "first sample above 0.1 m/s: %.4f m/s at rest\n",
              s[start].time_s, r.summary.reference_speed_m_s, median, first_crossing);
  EXPECT_GT(s[start].time_s, 599.0);  // not a noise spike while standing
  EXPECT_LT(s[start].time_s, 605.0);
  EXPECT_DOUBLE_EQ(r.summary.reference_speed_m_s, median);
  EXPECT_NEAR(r.summary.reference_speed_m_s, 5.0, 0.05);
  EXPECT_TRUE(has(r.notes, fmt::format("reference speed {:.4g} m/s", median)));
  EXPECT_TRUE(has(r.notes, "first 300 s of motion"));

  // a threshold from a known speed σ: 4·σ_v, stated in the summary
  Input in = sim.input;
  in.options.speed_sigma_m_s = 0.03;
  const Result k = process(in);
  EXPECT_DOUBLE_EQ(k.summary.stationary_speed_m_s, 0.12);
  EXPECT_TRUE(k.summary.stationary_from_speed_sigma);
  const nlohmann::json j = meridian::report::dov_summary_to_json(k);
  EXPECT_DOUBLE_EQ(j["stationary"]["threshold_m_s"].get<double>(), 0.12);
  EXPECT_EQ(j["stationary"]["threshold_from"], "speed_sigma_m_s");
  EXPECT_NEAR(j["stationary"]["reference_speed_m_s"].get<double>(), 5.0, 0.05);
  EXPECT_NE(meridian::report::dov_summary_text(k).find("stationary below 0.12 m/s"),
            std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// Whiteness.

Line moving_line(std::uint64_t seed, double tau_s) {
  Line line;
  line.duration_s = 600.0;
  line.speed = {{0, 5}, {600, 5}};
  line.ins_tau_s = tau_s;
  line.seed = seed;
  return line;
}

// White INS/GNSS noise: the Ljung–Box test (20 lags, α = 0.05) passes at about its nominal
// rate over 40 ten-minute lines (at most 2 × 5 % fail).
TEST(DovWhiteness, WhiteNoisePassesAtItsNominalRate) {
  int failed = 0;
  double mean_q = 0.0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    const Result r = process(simulate_line(moving_line(seed, 0.0)).input);
    const auto& w = r.summary.whiteness;
    EXPECT_EQ(w.lags, 20);
    EXPECT_DOUBLE_EQ(w.dof, 40.0);
    EXPECT_NEAR(w.critical_value, 55.758, 1e-3);  // χ²_0.95(40)
    mean_q += w.q / 40.0;
    if (!w.pass) {
      ++failed;
      EXPECT_TRUE(has(r.warnings, "not white"));
    } else {
      EXPECT_FALSE(has(r.warnings, "not white"));
    }
  }
  std::printf("white noise, 40 × 600 s: Ljung–Box failed %d of 40 (nominal 2), mean Q %.2f "
              "(expected 40)\n",
              failed, mean_q);
  EXPECT_LE(failed, 4);
}

// Gauss–Markov INS/GNSS attitude noise with the filter's own σ (0.5″) and τ = 10, 30, 60 s:
// the test fails on every line and the warning appears in the result, the JSON and the text
// summary. (The mean NIS is outside its interval here too, below it: the filter absorbs part of
// the slow noise into φ. The whiteness test names the cause.)
TEST(DovWhiteness, GaussMarkovNoiseFailsAndIsWarned) {
  for (double tau : {10.0, 30.0, 60.0})
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      const Result r = process(simulate_line(moving_line(seed, tau)).input);
      const auto& w = r.summary.whiteness;
      std::printf("Gauss–Markov τ %2.0f s, seed %llu: Q %.1f (critical %.1f), p %.2g; mean NIS "
                  "%.3f [%.3f, %.3f]\n",
                  tau, static_cast<unsigned long long>(seed), w.q, w.critical_value, w.p_value,
                  r.summary.mean_nis, r.summary.nis_interval.lower, r.summary.nis_interval.upper);
      EXPECT_FALSE(w.pass);
      EXPECT_TRUE(has(r.warnings, "not white"));
      if (tau == 30.0 && seed == 1) {
        const nlohmann::json j = meridian::report::dov_summary_to_json(r);
        EXPECT_EQ(j["whiteness"]["test"], "ljung_box");
        EXPECT_FALSE(j["whiteness"]["pass"].get<bool>());
        EXPECT_EQ(j["whiteness"]["lags"], 20);
        bool warned = false;
        for (const auto& s : j["warnings"])
          warned = warned || s.get<std::string>().find("Ljung–Box") != std::string::npos;
        EXPECT_TRUE(warned);
        const std::string text = meridian::report::dov_summary_text(r);
        EXPECT_NE(text.find("NOT white"), std::string::npos);
        EXPECT_NE(text.find("warning: the normalised innovations are not white"),
                  std::string::npos);
      }
    }
}

// The streaming Ljung–Box against the formula evaluated directly (two series, one of them
// autocorrelated), and its lag rule min(max_lag, ⌊n/5⌋).
TEST(DovWhiteness, LjungBoxAccumulatorMatchesTheFormula) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> nd;
  const std::size_t n = 333;
  std::vector<double> a(n), b(n);
  double prev = 0.0;
  for (std::size_t t = 0; t < n; ++t) {
    a[t] = 0.3 + nd(rng);
    prev = 0.6 * prev + nd(rng);
    b[t] = prev;
  }
  meridian::filter::LjungBox lb(2, 20);
  for (std::size_t t = 0; t < n; ++t) {
    const double v[2] = {a[t], b[t]};
    lb.add(v);
  }
  const auto direct = [&](const std::vector<double>& x, int h) {
    double mean = 0.0;
    for (double v : x) mean += v / static_cast<double>(x.size());
    double c0 = 0.0;
    for (double v : x) c0 += (v - mean) * (v - mean);
    double q = 0.0;
    for (int k = 1; k <= h; ++k) {
      double ck = 0.0;
      for (std::size_t t = static_cast<std::size_t>(k); t < x.size(); ++t)
        ck += (x[t] - mean) * (x[t - static_cast<std::size_t>(k)] - mean);
      q += (ck / c0) * (ck / c0) / static_cast<double>(x.size() - static_cast<std::size_t>(k));
    }
    const double nn = static_cast<double>(x.size());
    return nn * (nn + 2.0) * q;
  };
  const auto r = lb.result(0.05);
  EXPECT_EQ(r.lags, 20);
  EXPECT_NEAR(r.q, direct(a, 20) + direct(b, 20), 1e-9 * r.q);
  EXPECT_FALSE(r.pass);  // the AR(1) series
  const auto r7 = lb.result(0.01, 7);
  EXPECT_NEAR(r7.q, direct(a, 7) + direct(b, 7), 1e-9 * r7.q);
  EXPECT_EQ(meridian::filter::ljung_box_default_lags(49, 20), 9);
  EXPECT_EQ(meridian::filter::ljung_box_default_lags(4, 20), 0);
}

}  // namespace
