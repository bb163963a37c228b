// The self-checks of every method (issue 32, spec §6a) on lines simulated here from the physics
// — not by nav::simulate: a vessel steering a constant heading through water that moves with a
// current the dead reckoning does not know, its log measuring the speed through the water and
// its gyro the heading (white noise), range LOPs to shore stations and GNSS fixes with white
// noise. With a 1.1 m/s current method I loses the track and must say so (diverged, with the
// stretch); on clean lines (no current) no method may be marked.
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "meridian/nav/navigation.hpp"

namespace meridian::nav {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

struct Line {
  double duration_s = 3600.0;
  double speed_m_s = 5.0;       // through the water
  double heading_deg = 33.0;
  double current_m_s = 0.0;     // the water's velocity over the ground, unknown to the DR
  double current_to_deg = 225.0;
  std::vector<Eigen::Vector2d> stations;  // (north, east) m
  double lop_every_s = 5.0, sigma_lop_m = 30.0;
  double blunder_probability = 0.005, blunder_m = 300.0;
  double fix_every_s = 300.0, sigma_fix_m = 5.0;
  double sigma_speed_m_s = 0.05, sigma_heading_deg = 0.2;
};

// Truth: p(t) = p₀ + (v_water + current)·t (constant heading, speed and current: exact). The
// log: v_water with white noise in speed and heading, the covariance its first-order
// propagation. The initial position: truth + N(0, 10 m) per coordinate, stated as σ 10 m.
Input simulate_line(const Line& L, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n01(0.0, 1.0);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  Input in;
  const double h = L.heading_deg * kDeg;
  const Eigen::Vector2d water(L.speed_m_s * std::cos(h), L.speed_m_s * std::sin(h));
  const Eigen::Vector2d current(L.current_m_s * std::cos(L.current_to_deg * kDeg),
                                L.current_m_s * std::sin(L.current_to_deg * kDeg));
  const Eigen::Vector2d ground = water + current;
  const auto truth_at = [&](double t) -> Eigen::Vector2d { return ground * t; };
  for (std::size_t s = 0; s < L.stations.size(); ++s)
    in.stations.push_back({std::string(1, static_cast<char>('A' + s)), L.stations[s](0), L.stations[s](1)});
  const double ss = L.sigma_speed_m_s, sh = L.sigma_heading_deg * kDeg;
  for (double t = 0.0; t <= L.duration_s + 1e-9; t += 1.0) {
    const double v = L.speed_m_s + ss * n01(rng);
    const double a = h + sh * n01(rng);
    DrSample d;
    d.time_s = t;
    d.v_north_m_s = v * std::cos(a);
    d.v_east_m_s = v * std::sin(a);
    Eigen::Matrix2d J;
    J << std::cos(h), -L.speed_m_s * std::sin(h), std::sin(h), L.speed_m_s * std::cos(h);
    d.covariance = J * Eigen::Vector2d(ss * ss, sh * sh).asDiagonal() * J.transpose();
    in.dr.push_back(d);
    const Eigen::Vector2d p = truth_at(t);
    in.truth.push_back({t, p(0), p(1)});
  }
  for (double t = 0.4; t <= L.duration_s; t += L.lop_every_s)
    for (std::size_t s = 0; s < L.stations.size(); ++s) {
      Lop l;
      l.time_s = t;
      l.station = s;
      l.sigma_m = L.sigma_lop_m;
      l.value_m = (truth_at(t) - L.stations[s]).norm() + L.sigma_lop_m * n01(rng) +
                  (u01(rng) < L.blunder_probability ? L.blunder_m : 0.0);
      in.lops.push_back(l);
    }
  for (double t = L.fix_every_s + 0.7; t <= L.duration_s; t += L.fix_every_s) {
    const Eigen::Vector2d p = truth_at(t);
    Fix f;
    f.time_s = t;
    f.x_north_m = p(0) + L.sigma_fix_m * n01(rng);
    f.y_east_m = p(1) + L.sigma_fix_m * n01(rng);
    f.covariance = L.sigma_fix_m * L.sigma_fix_m * Eigen::Matrix2d::Identity();
    in.fixes.push_back(f);
  }
  in.initial.x_north_m = 10.0 * n01(rng);
  in.initial.y_east_m = 10.0 * n01(rng);
  in.initial.sigma_m = 10.0;
  return in;
}

Line current_line() {
  Line L;
  L.current_m_s = 1.1;
  L.stations = {{25000.0, -10000.0}, {-5000.0, 20000.0}, {40000.0, 30000.0}};
  return L;
}

const MethodResult& of(const Result& r, Method m) {
  const MethodResult* p = r.find(m);
  EXPECT_NE(p, nullptr) << to_string(m);
  return *p;
}

std::string describe(const MethodResult& m) {
  std::string t = to_string(m.method) + " " + to_string(m.consistency.status);
  for (const auto& a : m.consistency.alarms)
    t += "\n    " + a.check + " " + std::to_string(a.from_s) + "–" + std::to_string(a.to_s) + ": " + a.reason;
  return t;
}

// Measured over seeds 1–50 (docs/navigation.md): method I marked diverged in 50 of 50; the RTS
// smoother never marked; sequential-bias-II left unmarked in 4 of 50 although its truth NEES was
// 19–25 (RMS 23–26 m): a miss of the checks, not asserted here (seeds 1–4 have none).
TEST(NavConsistency, CurrentOf1p1MakesMethodIDivergeAndSaySo) {
  int diverged_i = 0, seeds = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed, ++seeds) {
    const Result r = process(simulate_line(current_line(), seed));
    const MethodResult& bi = of(r, Method::SequentialBiasI);
    ASSERT_TRUE(bi.errors);
    std::printf("seed %d: bias-I RMS %.1f m, %s\n", static_cast<int>(seed), bi.errors->rms_m,
                describe(bi).c_str());
    for (const auto& m : r.methods)
      std::printf("  %-20s RMS %8.1f m  NEES %9.2f  %s\n", to_string(m.method).c_str(), m.errors->rms_m,
                  m.errors->mean_nees, to_string(m.consistency.status).c_str());
    // Method I is really lost (truth: tens of metres to a kilometre off with a σ of a few metres),
    // and it says so, over a stretch of epochs, from the data alone.
    EXPECT_GT(bi.errors->mean_nees, 50.0);
    EXPECT_EQ(bi.consistency.status, MethodStatus::Diverged) << describe(bi);
    diverged_i += bi.consistency.status == MethodStatus::Diverged;
    bool fix_run = false;
    for (const auto& a : bi.consistency.alarms)
      if (a.check == "fix-run" && a.status == MethodStatus::Diverged) {
        fix_run = true;
        EXPECT_LT(a.from_epoch, a.to_epoch);
        EXPECT_EQ(a.from_s, r.find(Method::SequentialBiasI)->track[a.from_epoch].time_s);
        EXPECT_NE(a.reason.find("consecutive fixes"), std::string::npos) << a.reason;
      }
    EXPECT_TRUE(fix_run) << describe(bi);
    EXPECT_FALSE(bi.consistency.sigma_valid());
    // What inherits it is marked too, and the warnings say it (not silent).
    for (Method m : {Method::Backward, Method::FixClosure})
      EXPECT_EQ(of(r, m).consistency.status, MethodStatus::Diverged) << describe(of(r, m));
    bool warned = false;
    for (const auto& w : r.warnings) warned |= w.find("sequential-bias-I diverged") != std::string::npos;
    EXPECT_TRUE(warned);
    // The EKF and the RTS smoother estimate the current and accept the fixes: consistent, or
    // marked honestly — an unmarked method must be right (errors within a few σ: NEES).
    for (const auto& m : r.methods) {
      if (m.consistency.status != MethodStatus::Consistent) continue;
      EXPECT_LT(m.errors->mean_nees, 10.0) << to_string(m.method) << " is unmarked but its NEES is "
                                          << m.errors->mean_nees << " (RMS " << m.errors->rms_m << " m)";
    }
    EXPECT_EQ(of(r, Method::Rts).consistency.status, MethodStatus::Consistent) << describe(of(r, Method::Rts));
    EXPECT_LT(of(r, Method::Rts).errors->rms_m, 20.0);
  }
  std::printf("detection: method I marked diverged in %d of %d lines with a 1.1 m/s current\n", diverged_i, seeds);
}

// Clean lines (no current; the DR's σ right): two geometries × 10 seeds. A false alarm is a
// method marked although its σ did describe its errors (truth: mean NEES < 3, 2 expected). On
// the well-determined line (three stations, σ 30 m) nothing may be marked at all; on the weak
// one (two stations, σ 50 m, 4 m/s) the 1988 sequential methods' own σ are sometimes far too
// small (their bias estimate wanders), and marking them then is a detection, not a false alarm.
// The EKF and RTS are never marked. Measured over seeds 11–110 (docs/navigation.md): geometry 0
// 0 of 800 method runs marked; geometry 1 29 of 800, none of them with truth NEES < 3.
TEST(NavConsistency, NoFalseAlarmOnCleanLines) {
  std::vector<Line> geometries(2);
  geometries[0].stations = {{25000.0, -10000.0}, {-5000.0, 20000.0}, {40000.0, 30000.0}};
  geometries[1].heading_deg = 200.0;
  geometries[1].speed_m_s = 4.0;
  geometries[1].stations = {{-30000.0, 5000.0}, {10000.0, -25000.0}};
  geometries[1].fix_every_s = 180.0;
  geometries[1].sigma_lop_m = 50.0;
  int marked = 0, false_alarms = 0, runs = 0;
  for (std::size_t g = 0; g < geometries.size(); ++g)
    for (std::uint64_t seed = 11; seed <= 20; ++seed) {
      const Result r = process(simulate_line(geometries[g], seed));
      for (const auto& m : r.methods) {
        ++runs;
        if (m.consistency.status == MethodStatus::Consistent) continue;
        ++marked;
        std::printf("geometry %d seed %d: %s (truth: RMS %.1f m, NEES %.2f)\n", static_cast<int>(g),
                    static_cast<int>(seed), describe(m).c_str(), m.errors->rms_m, m.errors->mean_nees);
        const bool false_alarm = m.errors->mean_nees < 3.0;
        false_alarms += false_alarm;
        EXPECT_FALSE(false_alarm) << "false alarm: geometry " << g << " seed " << seed << ": " << describe(m);
        EXPECT_NE(g, 0u) << "the well-determined clean line marked " << describe(m);
        EXPECT_NE(m.method, Method::Ekf) << describe(m);
        EXPECT_NE(m.method, Method::Rts) << describe(m);
      }
    }
  std::printf("clean lines: %d of %d method runs marked, %d of them false alarms (truth NEES < 3)\n", marked,
              runs, false_alarms);
}

// The checks' statistics: a clean line's fix σ ratio near 1 for the EKF (its σ are rigorous).
TEST(NavConsistency, StatisticsOfACleanLine) {
  Line L;
  L.stations = {{25000.0, -10000.0}, {-5000.0, 20000.0}, {40000.0, 30000.0}};
  const Result r = process(simulate_line(L, 3));
  const Consistency& c = of(r, Method::Ekf).consistency;
  EXPECT_EQ(c.fixes_tested, 11u);
  EXPECT_EQ(c.fixes_outlying, 0u);
  EXPECT_GT(c.fix_sigma_ratio, 0.3);
  EXPECT_LT(c.fix_sigma_ratio, 2.0);
  EXPECT_EQ(c.lops_tested, r.lops_used);
  EXPECT_LT(c.max_rejected_share, 0.1);
  EXPECT_GT(c.max_innovation_ratio, 0.7);
  EXPECT_LT(c.max_innovation_ratio, 1.5);
  EXPECT_TRUE(std::isnan(of(r, Method::Rts).consistency.max_innovation_ratio));
}

}  // namespace
}  // namespace meridian::nav
