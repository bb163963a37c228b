#include "meridian/nav/simulator.hpp"

#include <cmath>
#include <random>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"

namespace meridian::nav {

Scenario scenario_from_string(const std::string& name) {
  if (name == "A" || name == "a") return Scenario::A;
  if (name == "B" || name == "b") return Scenario::B;
  if (name == "C" || name == "c") return Scenario::C;
  if (name == "D" || name == "d") return Scenario::D;
  throw InputError("unknown scenario \"" + name + "\" (A, B, C or D)", {{}, {}, "scenario"});
}

std::string to_string(Scenario s) {
  switch (s) {
    case Scenario::A: return "A";
    case Scenario::B: return "B";
    case Scenario::C: return "C";
    case Scenario::D: return "D";
  }
  return "?";
}

namespace {

void check(bool ok, const char* name, const std::string& what) {
  if (!ok) throw InputError(what, {{}, {}, std::string("simulation.") + name});
}

// Speed error e(I) of spec §8 (m/s) at sample I, time t = I·Δt.
double speed_error(Scenario s, long I, double t_s) {
  const double sine = 0.1 * std::sin(units::kPi * static_cast<double>(I) / 6.0);
  switch (s) {
    case Scenario::B: return sine;
    case Scenario::C: {
      const double minute = t_s / 60.0;
      return (minute >= 10.0 && minute < 15.0 ? 0.8 : 0.5) + sine;
    }
    case Scenario::A:
    case Scenario::D: break;
  }
  return 0.5 + sine;
}

// Every option in range (InputError "simulation.<name>").
void check_options(const SimulationOptions& o) {
  check(o.stations == 2 || o.stations == 3, "stations", "must be 2 or 3");
  check(std::isfinite(o.duration_s) && o.duration_s > 0.0, "duration_s", "must be > 0");
  check(std::isfinite(o.step_s) && o.step_s > 0.0, "step_s", "must be > 0");
  check(o.duration_s / o.step_s <= 1e7, "duration_s", "more than 10^7 samples");
  // nav::process needs at least 2 DR samples (at 0 and step_s): a shorter line would write a
  // job that cannot be processed.
  check(o.duration_s >= o.step_s - 1e-9, "duration_s",
        fmt::format("must be at least one DR step ({:g} s, for 2 DR samples), got {:g}", o.step_s,
                    o.duration_s));
  check(std::isfinite(o.speed_m_s) && o.speed_m_s > 0.0, "speed_m_s", "must be > 0");
  check(std::isfinite(o.heading_rad), "heading_rad", "must be finite");
  check(std::isfinite(o.sigma_range_m) && o.sigma_range_m > 0.0, "sigma_range_m", "must be > 0");
  check(o.blunder_probability >= 0.0 && o.blunder_probability < 1.0, "blunder_probability",
        "must be in [0, 1)");
  check(std::isfinite(o.blunder_min_m) && o.blunder_min_m >= 0.0 && o.blunder_max_m >= o.blunder_min_m &&
            std::isfinite(o.blunder_max_m),
        "blunder_max_m", "needs 0 <= blunder_min_m <= blunder_max_m");
  check(std::isfinite(o.sigma_speed_m_s) && o.sigma_speed_m_s >= 0.0, "sigma_speed_m_s", "must be >= 0");
  check(std::isfinite(o.sigma_heading_rad) && o.sigma_heading_rad >= 0.0, "sigma_heading_rad",
        "must be >= 0");
  check(std::isfinite(o.lop_interval_s) && o.lop_interval_s >= 0.0, "lop_interval_s", "must be >= 0");
  check(std::isfinite(o.fix_interval_s) && o.fix_interval_s >= 0.0, "fix_interval_s", "must be >= 0");
  check(std::isfinite(o.sigma_fix_m) && o.sigma_fix_m > 0.0, "sigma_fix_m", "must be > 0");
}

}  // namespace

SimulatedLine simulate(const SimulationOptions& o) {
  check_options(o);

  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);

  SimulatedLine line;
  Input& in = line.input;
  // Shore stations around a straight line of 9 km from the origin at 60° (the defaults):
  // ranges of 10 to 30 km, crossing angles between about 40° and 140° along the whole line.
  in.stations = {{"A", 20000.0, -5000.0}, {"B", -10000.0, -10000.0}, {"C", 5000.0, 30000.0}};
  in.stations.resize(static_cast<std::size_t>(o.stations));

  const double c = std::cos(o.heading_rad);
  const double s = std::sin(o.heading_rad);
  const auto samples = static_cast<long>(std::floor(o.duration_s / o.step_s + 1e-9));
  double next_fix = 0.0;
  double next_lop = 0.0;
  for (long I = 0; I <= samples; ++I) {
    const double t = static_cast<double>(I) * o.step_s;
    const double dist = o.speed_m_s * t;
    const Eigen::Vector2d truth(dist * c, dist * s);
    in.truth.push_back({t, truth(0), truth(1)});
    // DR: logged speed = true speed + e(I) + white noise, heading + white noise.
    const double v = o.speed_m_s + speed_error(o.scenario, I, t) + o.sigma_speed_m_s * normal(rng);
    const double a = o.heading_rad + o.sigma_heading_rad * normal(rng);
    in.dr.push_back(dr_from_speed_heading(t, v, a, o.sigma_speed_m_s, o.sigma_heading_rad));
    const bool lop_epoch = o.lop_interval_s <= 0.0 || t >= next_lop - 1e-9;
    if (lop_epoch && o.lop_interval_s > 0.0) next_lop += o.lop_interval_s;
    for (std::size_t st = 0; lop_epoch && st < in.stations.size(); ++st) {
      const double d =
          (truth - Eigen::Vector2d(in.stations[st].x_north_m, in.stations[st].y_east_m)).norm();
      Lop l;
      l.time_s = t;
      l.type = LopType::Range;
      l.station = st;
      l.sigma_m = o.sigma_range_m;
      l.value_m = d + o.sigma_range_m * normal(rng);
      if (uniform(rng) < o.blunder_probability) {
        const double size = o.blunder_min_m + (o.blunder_max_m - o.blunder_min_m) * uniform(rng);
        l.value_m += uniform(rng) < 0.5 ? -size : size;
        line.blunders.push_back(in.lops.size());
      }
      in.lops.push_back(l);
    }
    if (o.fix_interval_s > 0.0 && t >= next_fix - 1e-9) {
      Fix f;
      f.time_s = t;
      f.x_north_m = truth(0) + o.sigma_fix_m * normal(rng);
      f.y_east_m = truth(1) + o.sigma_fix_m * normal(rng);
      f.covariance = o.sigma_fix_m * o.sigma_fix_m * Eigen::Matrix2d::Identity();
      in.fixes.push_back(f);
      next_fix += o.fix_interval_s;
    }
  }
  // Initial position: the truth with an error drawn from its stated σ (10 m); scenario D:
  // 100 m north of the truth, stated as σ = 100 m (a start the user knows to be poor).
  if (o.scenario == Scenario::D) {
    in.initial = {100.0, 0.0, 100.0};
  } else {
    in.initial.sigma_m = 10.0;
    in.initial.x_north_m = 10.0 * normal(rng);
    in.initial.y_east_m = 10.0 * normal(rng);
  }
  line.settings = fmt::format(
      "scenario {} seed {} stations {} duration_s {:g} step_s {:g} lop_interval_s {:g} speed_m_s {:g} heading_deg {:g} "
      "sigma_range_m {:g} blunder_probability {:g} blunder_m {:g}..{:g} sigma_speed_m_s {:g} "
      "sigma_heading_deg {:g} fix_interval_s {:g} sigma_fix_m {:g} initial ({:.3f}, {:.3f}) "
      "sigma_m {:g}",
      to_string(o.scenario), o.seed, o.stations, o.duration_s, o.step_s, o.lop_interval_s, o.speed_m_s,
      o.heading_rad / units::kDegree, o.sigma_range_m, o.blunder_probability, o.blunder_min_m,
      o.blunder_max_m, o.sigma_speed_m_s, o.sigma_heading_rad / units::kDegree, o.fix_interval_s,
      o.sigma_fix_m, in.initial.x_north_m, in.initial.y_east_m, in.initial.sigma_m);
  return line;
}

}  // namespace meridian::nav
