#include "meridian/report/gyro_html.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "gyro_plots.hpp"
#include "meridian/report/format.hpp"
#include "meridian/report/gyro_text.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/angle.hpp"
#include "meridian/core/units.hpp"
#include "meridian/geodesy/grid.hpp"

namespace meridian::report {
namespace {

using fmtx::num;
using nlohmann::json;
using namespace gyro_plots;

// ---------------------------------------------------------------- tables

Table methods_table(const gyro::DeterminationResult& r, const AngleFormat& f) {
  const bool all = !r.method;
  const std::vector<gyro::MethodResult>& ms = all ? r.all : std::vector<gyro::MethodResult>{r.primary};
  // Method names, the reported one marked when all were run.
  auto name = [&](const gyro::MethodResult& m) {
    return gyro::to_string(m.method) + (all && m.method == r.primary.method ? " (reported)" : "");
  };
  Table t;
  t.title = all ? "Every applicable method" : "Result";
  if (r.mode == gyro::Mode::NonTracking) {
    t.columns = {"method", "beta (div)", "sigma beta (div)", "delta N", "N_G", "sigma N_G", "approximation error", "warnings"};
    t.numeric = {false, true, true, true, true, true, true, false};
    for (const auto& m : ms) {
      std::string w;
      if (m.beta)
        for (const auto& x : m.beta->warnings) w += (w.empty() ? "" : "; ") + x;
      t.rows.push_back({name(m),
                        m.beta ? num(m.beta->beta_div.value, 5) : "",
                        m.beta ? num(m.beta->beta_div.sigma, 5) : "", f.sec(m.north.delta_n_rad, 3),
                        f.dir(m.north.north_rad, 2), f.sig(m.north.sigma_rad, 2),
                        m.approximation_error_rad != 0.0 ? f.sec(m.approximation_error_rad, 3) : "exact", w});
    }
  } else {
    t.columns = {"method", "N_G", "sigma N_G", "dof", "sigma0 (arcsec)", "sigma basis"};
    t.numeric = {false, true, true, true, true, false};
    for (const auto& m : ms) {
      const auto& fit = *m.reversal;
      t.rows.push_back({name(m), f.dir(m.north.north_rad, 2), f.sig(m.north.sigma_rad, 2),
                        std::to_string(fit.dof), num(fit.sigma0 / units::kArcsecond, 2),
                        fit.sigma_from_gls ? "GLS, correlated readings"
                        : std::isfinite(fit.centre.sigma)
                            ? (fit.sigma_is_aposteriori ? "a posteriori" : "a priori")
                            : "n/a"});
    }
  }
  return t;
}

Table fit_table(const gyro::UnifiedFitResult& fit) {
  Table t;
  t.title = "Unified least-squares fit of (N1)";
  t.columns = {"parameter", "estimate", "sigma", "unit"};
  t.numeric = {false, true, true, false};
  t.rows = {{"beta (equilibrium reading)", num(fit.beta_div.value, 5), num(fit.beta_div.sigma, 5), "div"},
            {"B (amplitude at t0)", num(fit.amplitude_div.value, 4), num(fit.amplitude_div.sigma, 4), "div"},
            {"t0 (eastward passage of beta)", num(fit.t0_s.value, 3), num(fit.t0_s.sigma, 3), "s"},
            {"T_B (period)", num(fit.period_s.value, 3), num(fit.period_s.sigma, 3), "s"},
            {"k (damping)", fmt::format("{:.3g}", fit.damping_per_s.value), fmt::format("{:.3g}", fit.damping_per_s.sigma), "1/s"}};
  t.note = fmt::format("sigma are a priori (from the stated observation sigma); sigma0 = {}, {} degrees of freedom, "
                       "{} iterations.",
                       num(fit.sigma0, 3), fit.dof, fit.iterations);
  return t;
}

// Stopwatch time as m:ss.s.
std::string mss(double s) {
  const double whole_min = std::floor(s / 60.0);
  return fmt::format("{:.0f}:{:04.1f}", whole_min, s - 60.0 * whole_min);
}

std::string numbers(const std::vector<double>& v, int decimals) {
  std::string out;
  for (double x : v) out += (out.empty() ? "" : ", ") + num(x, decimals);
  return out;
}

// Non-tracking: the passages and reversal readings as booked, and the
// quantities the reduction took from them, so a checker can redo it by hand.
std::vector<Block> nontracking_observation_blocks(const gyro::DeterminationInput& in, const gyro::DeterminationResult& r,
                                                  const gyro::Instrument& inst) {
  const auto& o = in.nontracking;
  std::vector<Block> b;
  Table t;
  t.title = "Timed passages as booked (观测手簿)";
  t.columns = {"crossings", "level (div)", "first passage", "times (s)", "times (m:ss.s)",
               "half-periods t[j+1] - t[j] (s), east/west alternate", "t3 - t1 (s)",
               "dt of each triple, (-1)^j (-t[j] + 2 t[j+1] - t[j+2]) (s)"};
  t.numeric = {false, true, false, true, true, true, true, true};
  std::size_t most_times = 0;
  for (std::size_t i = 0; i < o.crossings.size(); ++i) {
    const auto& c = o.crossings[i];
    const auto& ts = c.times_s;
    most_times = std::max(most_times, ts.size());
    std::string m;
    for (double x : ts) m += (m.empty() ? "" : ", ") + mss(x);
    std::vector<double> half, triples;
    for (std::size_t j = 0; j + 1 < ts.size(); ++j) half.push_back(ts[j + 1] - ts[j]);
    // Referred to the first passage's direction: a triple starting on the other direction
    // changes sign.
    for (std::size_t j = 0; j + 2 < ts.size(); ++j)
      triples.push_back((j % 2 == 0 ? 1.0 : -1.0) * (-ts[j] + 2 * ts[j + 1] - ts[j + 2]));
    t.rows.push_back({fmt::format("[{}]", i), num(c.level_div, 2), c.first_direction > 0 ? "east" : "west",
                      numbers(ts, 1), m, numbers(half, 1), ts.size() >= 3 ? num(ts[2] - ts[0], 1) : "",
                      numbers(triples, 2)});
  }
  if (o.crossings.size() == 1 && most_times == 5) {
    // Five transits, T_B unknown: the least-squares dt in closed form (spec 4.1), for a checker.
    const auto& ts = o.crossings.front().times_s;
    t.note = fmt::format(
        "Five transits: least squares with T_B unknown gives dt = (-2 t1 + 3 t2 - 2 t3 + 3 t4 - 2 t5)/3 = {} s "
        "from the times above (spec 4.1); the dt used is below.",
        num((-2 * ts[0] + 3 * ts[1] - 2 * ts[2] + 3 * ts[3] - 2 * ts[4]) / 3.0, 2));
  }
  b.push_back(t);
  std::vector<KeyValue> kv;
  if (!o.reversals_div.empty()) kv.push_back({"reversal readings (div)", numbers(o.reversals_div, 2)});
  if (o.period_s) kv.push_back({"period T_B booked", num(o.period_s->value, 1) + " s"});
  if (const auto& beta = r.primary.beta) {
    if (beta->amplitude_div) kv.push_back({"amplitude B used", num(beta->amplitude_div->value, 3) + " div"});
    if (beta->period_s) kv.push_back({"period T_B used", num(beta->period_s->value, 2) + " s"});
    if (beta->time_difference_s)
      kv.push_back({"transit time difference dt used", fmt::format("{} s (sigma {} s){}", num(beta->time_difference_s->value, 2),
                                                                  num(beta->time_difference_s->sigma, 2),
                                                                  most_times > 3 ? ", least squares over every passage"
                                                                                 : "")});
    if (r.primary.method == gyro::Method{gyro::NonTrackingMethod::Transit}) {
      if (inst.transit_factor_rad_per_div_s)
        kv.push_back({"transit factor c used (calibrated)",
                      fmt::format("{:.4f}\"/(div s)",
                                  inst.transit_factor_rad_per_div_s->value / units::kArcsecond)});
      else if (beta->period_s)
        kv.push_back(
            {"transit factor c used (computed (1+lambda) tau pi/(2 T_B))",
             fmt::format("{:.4f}\"/(div s)",
                         (1.0 + inst.torsion_ratio.value) * inst.scale_value_rad * units::kPi /
                             (2.0 * beta->period_s->value) / units::kArcsecond)});
    }
  }
  if (!kv.empty()) b.push_back(KeyValueList{"Quantities of the reduction", kv});
  return b;
}

// Tracking: the reversal readings and the successive Schuler means.
Table tracking_observation_table(const gyro::DeterminationInput& in, const gyro::DeterminationResult& r,
                                 const AngleFormat& f) {
  Table t;
  t.title = "Reversal readings as booked";
  t.columns = {"#", "circle reading", "successive Schuler mean (r[i-2] + 2 r[i-1] + r[i])/4"};
  t.numeric = {true, true, true};
  const auto& means = r.primary.reversal ? r.primary.reversal->partial_means : std::vector<double>{};
  const auto& rev = in.tracking.reversals_rad;
  for (std::size_t i = 0; i < rev.size(); ++i)
    t.rows.push_back({std::to_string(i + 1), f.dir(rev[i], 0), i >= 2 && i - 2 < means.size() ? f.dir(means[i - 2], 1) : ""});
  if (means.size() >= 2) {
    const auto [lo, hi] = std::minmax_element(means.begin(), means.end(), [&](double a, double b) {
      return wrap_signed_rad(a - means.front()) < wrap_signed_rad(b - means.front());
    });
    t.note = fmt::format("The successive Schuler means spread by {}.", f.sig(wrap_signed_rad(*hi - *lo), 1));
  }
  return t;
}

// The motor-off runs as booked with their centres.
Table zero_position_table(const gyro::DeterminationInput& in, const gyro::ZeroPositionSummary& z) {
  Table t;
  t.title = "Zero position (motor off) as booked";
  t.columns = {"run", "reversal readings (div)", "centre alpha_p (div)", "amplitude (div)"};
  t.numeric = {false, true, true, true};
  auto row = [&](const char* name, const std::optional<gyro::ZeroPositionRun>& run,
                 const std::optional<gyro::ZeroPositionEstimate>& e) {
    if (run && e)
      t.rows.push_back({name, numbers(run->reversals_div, 2), num(e->fit.centre.value, 3), num(e->amplitude_div, 2)});
  };
  row("before", in.zero_before, z.before);
  row("after", in.zero_after, z.after);
  t.note = fmt::format("alpha_p used: {} div (sigma {}).", num(z.mean_div.value, 3), num(z.mean_div.sigma, 3));
  return t;
}

// The target rounds: faces, 2C and each round's direction.
Table target_table(const gyro::DeterminationInput& in, const gyro::TargetDirection& d, const AngleFormat& f) {
  Table t;
  t.title = "Target pointings (rounds)";
  t.columns = {"round", "face left", "face right", "2C", "direction (L + R - 180)/2"};
  t.numeric = {false, true, true, true, true};
  for (std::size_t i = 0; i < in.target_rounds.size(); ++i) {
    const auto& r = in.target_rounds[i];
    t.rows.push_back({r.when == gyro::TargetRound::When::Before ? "before the run" : "after the run",
                      f.dir(r.face_left_rad, 0), f.dir(r.face_right_rad, 0), f.sec(d.two_c_rad[i], 0), f.dir(d.round_rad[i], 1)});
  }
  t.note = fmt::format("Target reading used: {} (sigma {}); rounds spread by {}.", f.dir(d.reading_rad.value, 1),
                       f.sig(d.reading_rad.sigma, 1), f.sig(d.spread_rad, 1));
  return t;
}

// All blocks describing one determination.
std::vector<Block> determination_blocks(const gyro::DeterminationInput& in, const gyro::DeterminationResult& r,
                                        const gyro::Instrument& inst, const AngleFormat& f) {
  std::vector<Block> b;
  std::vector<KeyValue> kv{{"mode", gyro::to_string(r.mode)}, {"method requested", gyro::method_request_name(r.method)},
                           {"reported method", gyro::to_string(r.primary.method)},
                           {"N_G (gyro north as a circle reading)", f.dir(r.primary.north.north_rad, 2)},
                           {"sigma N_G", f.sig(r.primary.north.sigma_rad, 2)}};
  if (r.mode == gyro::Mode::NonTracking) {
    kv.push_back({"clamp reading N'", f.dir(in.clamp_reading_rad, 1)});
    kv.push_back({"delta N = N_G - N'", f.sec(r.primary.north.delta_n_rad, 3)});
  }
  if (r.zero_position_used)
    kv.push_back({"zero position alpha_p / correction -lambda tau alpha_p",
                  fmt::format("{} div (sigma {}) / {}", num(r.zero_position_used->value, 3),
                              num(r.zero_position_used->sigma, 3), f.sec(r.primary.north.zero_correction_rad, 2))});
  else
    kv.push_back({"zero position", "not given: no zero-position correction applied"});
  if (r.target) kv.push_back({"circle reading to the target (mean of the rounds)", f.dir(r.target->reading_rad.value, 1)});
  else if (in.target_reading_rad)
    kv.push_back({"circle reading to the target", f.dir(in.target_reading_rad->value, 1)});
  if (!in.time.empty()) kv.push_back({"time", in.time});
  if (!in.observer.empty()) kv.push_back({"observer", in.observer});
  b.push_back(KeyValueList{"", kv});
  if (r.mode == gyro::Mode::NonTracking) {
    for (auto& x : nontracking_observation_blocks(in, r, inst)) b.push_back(std::move(x));
  } else {
    b.push_back(tracking_observation_table(in, r, f));
  }
  if (r.zero_position) b.push_back(zero_position_table(in, *r.zero_position));
  if (r.target) b.push_back(target_table(in, *r.target, f));
  b.push_back(methods_table(r, f));
  if (r.mode == gyro::Mode::NonTracking) {
    const gyro::UnifiedFitResult* fit = r.primary.fit ? &*r.primary.fit : nullptr;
    if (!fit)
      for (const auto& m : r.all)
        if (m.fit) fit = &*m.fit;
    b.push_back(oscillation_plot(in, fit, r.primary.beta ? &*r.primary.beta : nullptr));
    if (fit) {
      b.push_back(fit_table(*fit));
      b.push_back(fit_residual_plot(*fit));
    }
  } else if (r.primary.reversal) {
    b.push_back(tracking_plot(in, *r.primary.reversal, f));
    if (r.primary.reversal->dof > 0) b.push_back(tracking_residual_plot(*r.primary.reversal));
  }
  if (!r.method && r.all.size() > 1) b.push_back(methods_plot(r));
  if (r.zero_position) b.push_back(zero_position_plot(in, *r.zero_position));
  b.push_back(Notes{"Warnings", r.warnings, true});
  return b;
}

std::vector<KeyValue> instrument_header(const gyro::InstrumentSpec& s, const gyro::Instrument& at_station) {
  std::vector<KeyValue> h;
  if (!s.name.empty()) h.push_back({"instrument", s.name});
  h.push_back(
      {"scale value tau", fmt::format("{:.2f}\"/div", s.scale_value_rad / units::kArcsecond)});
  if (s.torsion_ratio)
    h.push_back(
        {"torsion ratio lambda (given)",
         fmt::format("{:.5f} (sigma {:.5f}){}", s.torsion_ratio->value, s.torsion_ratio->sigma,
                     s.constants_latitude_rad
                         ? fmt::format(" at latitude {:.4f} deg",
                                       *s.constants_latitude_rad / units::kDegree)
                         : "")});
  h.push_back({"torsion ratio lambda at the station",
               fmt::format("{:.5f} (sigma {:.5f})", at_station.torsion_ratio.value, at_station.torsion_ratio.sigma)});
  if (at_station.transit_factor_rad_per_div_s)
    h.push_back({"calibrated transit factor c",
                 fmt::format("{:.4f}\"/(div s)",
                             at_station.transit_factor_rad_per_div_s->value / units::kArcsecond)});
  h.push_back({"observation sigma", fmt::format("time {} s, scale reading {} div", s.sigma_time_s, s.sigma_reading_div)});
  h.push_back({"accuracy class", fmt::format("{}\"", s.accuracy_class_arcsec)});
  return h;
}

std::string point_text(const gyro::PointResult& p, const AngleFormat& f) {
  return fmt::format("{}: latitude {}, longitude {}; x {:.3f} m, y {:.3f} m; convergence {}", p.name,
                     format_dms(Angle::radians(p.lat_rad), {3, true, false}),
                     format_dms(Angle::radians(p.lon_rad), {3, true, false}), p.grid.x_north_m, p.grid.y_east_m,
                     f.dms(p.grid.convergence_rad, 2));
}

// The stochastic model behind N_G: "white", "markov1-ml", "white (markov1 not usable)".
std::string stochastic_cell(const gyro::StochasticUse& u) {
  return u.fallback ? fmt::format("{} ({} not usable)", u.used, gyro::to_string(u.requested)) : u.used;
}

std::string label_of(const gyro::DeterminationResult& d, std::size_t i) {
  return d.label.empty() ? fmt::format("#{} ({})", i + 1, gyro::to_string(d.primary.method)) : d.label;
}

// ---------------------------------------------------------------- sections

Section reduce_summary_section(const gyro::ReduceResult& r, const AngleFormat& f) {
  Section summary{"summary", "Summary", {}, 2};
  Table t;
  t.title = "N_G of every determination";
  t.columns = {"#", "label", "mode", "method", "N_G", "sigma", "delta N"};
  t.numeric = {true, false, false, false, true, true, true};
  for (std::size_t i = 0; i < r.determinations.size(); ++i) {
    const auto& d = r.determinations[i];
    t.rows.push_back({std::to_string(i + 1), d.label, gyro::to_string(d.mode), gyro::to_string(d.primary.method),
                      f.dir(d.primary.north.north_rad, 2), f.sig(d.primary.north.sigma_rad, 2),
                      f.sec(d.primary.north.delta_n_rad, 3)});
  }
  summary.blocks.push_back(t);
  summary.blocks.push_back(Notes{"Notes", r.instrument.notes, false});
  return summary;
}

std::string line_name(const gyro::CampaignResult& r) {
  return r.station.name + (r.target ? " to " + r.target->name : "");
}

// The labels of the result sheet in the job's language (RecordSheet::language): English, or
// Chinese with the English term beside it, as a mine files it.
struct SheetLabels {
  bool zh = false;
  std::string operator()(const char* en, const char* cn) const {
    return zh ? fmt::format("{} {}", cn, en) : std::string(en);
  }
};

// The one-page result sheet (成果表) that goes to the mine: the result, what it rests on (the
// known line, E before and after, the runs), gyro minus traverse, whether every check passed,
// the warnings, and who answers for it.
Section result_sheet_section(const gyro::CampaignInput& in, const gyro::CampaignResult& r, const AngleFormat& f) {
  const SheetLabels L{in.record.language == "zh"};
  const auto& c = r.chain;
  Section s{"result-sheet", L("Result sheet", "陀螺定向成果表"), {}, 2};
  s.page_break_after = true;
  int failed = 0;
  for (const auto& k : r.checks) failed += k.pass ? 0 : 1;
  const std::string detail =
      failed == 0 ? fmt::format("{}: {}", L("all checks pass", "全部检核合格"), r.checks.size())
                  : fmt::format("{} OF {} CHECKS FAILED: do not use this azimuth before they are resolved{}", failed,
                                r.checks.size(), L.zh ? " (检核不合格, 不得使用)" : "");
  s.blocks.push_back(Highlight{L("Grid azimuth", "坐标方位角") + " " + line_name(r),
                               f.dir(c.grid_azimuth_rad.value, 1) + "  \u00b1 " + f.sig(c.grid_azimuth_rad.sigma, 1), detail,
                               failed > 0});
  std::vector<KeyValue> job;
  if (!r.name.empty()) job.push_back({L("job", "工程"), r.name});
  if (!in.record.date.empty()) job.push_back({L("date", "日期"), in.record.date});
  const std::string& serial = in.instrument.serial;
  job.push_back({L("instrument", "仪器"),
                 (in.instrument.name.empty() ? std::string("gyro-theodolite") : in.instrument.name) +
                     (serial.empty() || in.instrument.name.find(serial) != std::string::npos ? "" : ", No. " + serial) +
                     fmt::format(", {:g}\" class{}", r.limits.accuracy_class_arcsec,
                                 in.instrument.accuracy_class_booked ? "" : " (NOT BOOKED: the class used)")});
  if (in.known_line)
    job.push_back({L("programme (runs before / on the line / after)", "观测程序 (测前 / 定向边 / 测后)"),
                   fmt::format("{}-{}-{}", in.known_line->before.size(), in.line.determinations.size(),
                               in.known_line->after.size())});
  job.push_back({L("station", "测站") + " " + r.station.name,
                 fmt::format("{} {}, {} {}", L("latitude", "纬度"), format_dms(Angle::radians(r.station.lat_rad), {2, true, false}),
                             L("longitude", "经度"), format_dms(Angle::radians(r.station.lon_rad), {2, true, false}))});
  job.push_back({L("grid", "坐标系"), geodesy::describe(in.grid)});
  if (!in.record.weather.empty()) job.push_back({L("weather", "天气"), in.record.weather});
  if (!in.record.temperature.empty()) job.push_back({L("temperature", "温度"), in.record.temperature});
  if (!in.record.remarks.empty()) job.push_back({L("remarks", "备注"), in.record.remarks});
  s.blocks.push_back(KeyValueList{L("Job", "工程概况"), job});

  Table t;
  t.title = L("Result", "成果");
  t.columns = {L("quantity", "项目"), L("value", "数值"), L("sigma", "中误差")};
  t.numeric = {false, true, true};
  t.rows.push_back({L("grid azimuth T", "坐标方位角 T") + " " + line_name(r), f.dir(c.grid_azimuth_rad.value, 1),
                    f.sig(c.grid_azimuth_rad.sigma, 1)});
  if (r.line_grid_azimuth_from_coordinates_rad) {
    t.rows.push_back({L("azimuth of the coordinates (traverse)", "导线坐标方位角"),
                      f.dir(*r.line_grid_azimuth_from_coordinates_rad, 1), ""});
    // Its limit beside it: the sheet is read on its own (helper trial, issue 36).
    std::string limit;
    for (const auto& k : r.checks)
      if (k.field == "line.to" && k.name.find("azimuth of its coordinates") != std::string::npos)
        limit = fmt::format("{} \u00b1{:.1f}\" {}", L("limit", "限差"), k.tolerance,
                            k.pass ? L("PASS", "合格") : L("FAIL", "不合格"));
    t.rows.push_back({L("gyro minus traverse azimuth", "陀螺方位角与导线方位角之差"),
                      f.sec(wrap_signed_rad(c.grid_azimuth_rad.value - *r.line_grid_azimuth_from_coordinates_rad), 1),
                      limit});
  }
  t.rows.push_back({L("geodetic azimuth alpha", "大地方位角 α"), f.dir(c.geodetic_azimuth_rad.value, 1),
                    f.sig(c.geodetic_azimuth_rad.sigma, 1)});
  t.rows.push_back({L("astronomic azimuth A", "天文方位角 A"), f.dir(c.astronomic_azimuth_rad.value, 1),
                    f.sig(c.astronomic_azimuth_rad.sigma, 1)});
  if (r.instrument_constant) {
    const auto mean_of = [](const std::vector<Uncertain>& v) -> std::optional<double> {
      if (v.empty()) return std::nullopt;
      return gyro::mean_direction(v).mean.value;
    };
    const auto& e = *r.instrument_constant;
    if (auto b = mean_of(e.before))
      t.rows.push_back({L("instrument constant E, mean before", "仪器常数 E (测前平均)"), f.sec(wrap_signed_rad(*b), 1), ""});
    if (auto a = mean_of(e.after))
      t.rows.push_back({L("instrument constant E, mean after", "仪器常数 E (测后平均)"), f.sec(wrap_signed_rad(*a), 1), ""});
    if (e.difference_rad)
      t.rows.push_back({L("E after minus before", "测后与测前之差"), f.sec(*e.difference_rad, 1), ""});
  }
  t.rows.push_back({L("instrument constant E used", "仪器常数 E"), f.sec(r.instrument_constant_used_rad.value, 1),
                    f.sig(r.instrument_constant_used_rad.sigma, 1)});
  if (r.constant_one_run_sigma_rad)
    t.rows.push_back({L("instrument constant, one run m", "仪器常数一次测定中误差"), "", f.sig(*r.constant_one_run_sigma_rad, 1)});
  t.rows.push_back({fmt::format("{} ({} {})", L("gyro azimuth A_G, mean", "陀螺方位角 A_G 平均"), r.gyro_azimuths.size(),
                                L("runs", "测回")),
                    f.dir(c.gyro_azimuth_rad.value, 1), f.sig(c.gyro_azimuth_rad.sigma, 1)});
  if (r.line_one_run_sigma_rad)
    t.rows.push_back({L("gyro azimuth, one run m", "陀螺方位角一次测定中误差"), "", f.sig(*r.line_one_run_sigma_rad, 1)});
  t.rows.push_back({L("meridian convergence gamma at", "子午线收敛角 γ") + " " + r.station.name, f.dms(c.convergence_rad, 2), ""});
  for (const auto* p : {&r.station, r.target ? &*r.target : nullptr})
    if (p)
      t.rows.push_back({L("coordinates of", "坐标") + " " + p->name,
                        fmt::format("x {:.3f} m, y {:.3f} m", p->grid.x_north_m, p->grid.y_east_m), ""});
  s.blocks.push_back(t);

  if (in.known_line && r.known_station) {
    const auto& k = *in.known_line;
    std::vector<KeyValue> kl;
    kl.push_back({L("given azimuth", "已知方位角") + " " + r.known_station->name +
                      (r.known_target ? " to " + r.known_target->name : ""),
                  fmt::format("{} ({}), {} {}", f.dir(k.azimuth.value_rad.value, 1), geodesy::to_string(k.azimuth.kind),
                              L("sigma", "中误差"), f.sig(k.azimuth.value_rad.sigma, 1))});
    for (const auto* p : {&*r.known_station, r.known_target ? &*r.known_target : nullptr})
      if (p)
        kl.push_back({L("coordinates of", "坐标") + " " + p->name,
                      fmt::format("x {:.3f} m, y {:.3f} m", p->grid.x_north_m, p->grid.y_east_m)});
    if (r.known_grid_azimuth_from_coordinates_rad)
      kl.push_back({L("azimuth of its coordinates", "坐标反算方位角"), f.dir(*r.known_grid_azimuth_from_coordinates_rad, 1)});
    s.blocks.push_back(KeyValueList{L("Known line", "已知边"), kl});
  }

  // Every run: when, which mode, and what it gave (E on the known line, A_G on the line).
  Table runs;
  runs.title = L("Runs", "观测测回");
  runs.columns = {L("run", "测回"), L("time", "时间"), L("mode", "方法"), L("result", "结果")};
  runs.numeric = {false, false, false, true};
  const auto add_runs = [&](const std::vector<gyro::DeterminationInput>& din, const std::vector<gyro::DeterminationResult>& dr,
                            const std::vector<Uncertain>* e, const std::vector<Uncertain>* ag, const char* what) {
    for (std::size_t i = 0; i < dr.size() && i < din.size(); ++i) {
      std::string value;
      if (e && i < e->size()) value = "E " + f.sec(wrap_signed_rad((*e)[i].value), 1);
      else if (ag && i < ag->size()) value = "A_G " + f.dir((*ag)[i].value, 1);
      runs.rows.push_back({fmt::format("{} {}", what, label_of(dr[i], i)), din[i].time, gyro::to_string(dr[i].mode), value});
    }
  };
  if (in.known_line) {
    const auto* ic = r.instrument_constant ? &*r.instrument_constant : nullptr;
    add_runs(in.known_line->before, r.known_before, ic ? &ic->before : nullptr, nullptr, L.zh ? "测前" : "before:");
    add_runs(in.known_line->after, r.known_after, ic ? &ic->after : nullptr, nullptr, L.zh ? "测后" : "after:");
  }
  add_runs(in.line.determinations, r.determinations, nullptr, &r.gyro_azimuths, L.zh ? "定向边" : "line:");
  s.blocks.push_back(runs);

  if (failed > 0) {
    std::vector<std::string> items;
    for (const auto& k : r.checks)
      if (!k.pass) items.push_back(check_text(k));
    s.blocks.push_back(Notes{L("Failed checks", "不合格检核"), items, true});
  }
  if (!r.warnings.empty()) s.blocks.push_back(Notes{L("Warnings", "警告"), r.warnings, true});
  s.blocks.push_back(Signatures{{{L("observer", "观测者"), in.record.observer},
                                 {L("booker", "记录者"), in.record.booker},
                                 {L("computed by", "计算者"), in.record.computed_by},
                                 {L("checked by", "检查者"), in.record.checked_by}},
                                {L("name", "姓名"), L("signature", "签名"), L("date", "日期")}});
  return s;
}

// The grid azimuth and every step of the chain from the field data to it.
// The chain from field data to the grid azimuth: the 计算表 (computation sheet) of the job.
Section campaign_result_section(const gyro::CampaignResult& r, const AngleFormat& f) {
  const SheetLabels L{r.input.record.language == "zh"};
  const auto& c = r.chain;
  Section result{"result", L("Computation sheet", "计算表"), {}, 2};
  result.blocks.push_back(Highlight{L("Grid azimuth", "坐标方位角") + " " + line_name(r),
                                    f.dir(c.grid_azimuth_rad.value, 1) + "  \u00b1 " + f.sig(c.grid_azimuth_rad.sigma, 1),
                                    r.all_checks_pass() ? L("all tolerance checks pass", "全部检核合格")
                                                        : L("SOME TOLERANCE CHECKS FAIL", "检核不合格")});
  Table chain;
  chain.title = L("From field data to grid azimuth", "由观测值到坐标方位角");
  chain.columns = {L("quantity", "项目"), L("value", "数值"), L("sigma", "中误差"), L("how", "说明")};
  chain.numeric = {false, true, true, false};
  chain.rows = {
      {L("gyro azimuth A_G (mean of the line's determinations)", "陀螺方位角 A_G (定向边各测回平均)"),
       f.dir(c.gyro_azimuth_rad.value, 2), f.sig(c.gyro_azimuth_rad.sigma, 2),
       fmt::format("{} determinations; A_G = r - N_G", r.determinations.size())},
      {L("instrument constant E", "仪器常数 E"), f.sec(r.instrument_constant_used_rad.value, 2),
       f.sig(r.instrument_constant_used_rad.sigma, 2),
       r.instrument_constant ? L("calibrated on the known line", "已知边上测定") : L("given", "给定")},
      {L("astronomic azimuth A = A_G + E", "天文方位角 A = A_G + E"), f.dir(c.astronomic_azimuth_rad.value, 2),
       f.sig(c.astronomic_azimuth_rad.sigma, 2), ""},
      {L("Laplace correction -eta tan(phi)", "拉普拉斯改正 -η tan φ"),
       c.laplace_applied ? f.sec(c.laplace_correction_rad, 2) : L("not applied", "未加"), "",
       c.laplace_applied ? "eta at the station" : "eta unknown"},
      {L("zenith-distance term -(xi sin alpha - eta cos alpha) cot z", "天顶距项 -(ξ sin α - η cos α) cot z"),
       c.zenith_term_applied ? f.sec(c.zenith_correction_rad, 2) : L("not applied", "未加"), "",
       c.zenith_term_applied ? "z = " + format_dms(Angle::radians(*c.zenith_distance_rad), {0, true, false})
                             : "sight horizontal, or xi/eta unknown"},
      {L("geodetic azimuth alpha", "大地方位角 α"), f.dir(c.geodetic_azimuth_rad.value, 2),
       f.sig(c.geodetic_azimuth_rad.sigma, 2), ""},
      {L("meridian convergence gamma (subtracted)", "子午线收敛角 γ (减)"), f.dms(c.convergence_rad, 2), "exact",
       "GeographicLib transverse Mercator"},
      {L("arc-to-chord correction delta (added)", "方向改化 δ (加)"),
       c.arc_to_chord_applied ? f.sec(c.arc_to_chord_rad, 2) : L("not applied", "未加"),
       c.arc_to_chord_applied ? "exact" : "", c.arc_to_chord_applied ? "rigorous, from the geodesic" : "no target coordinates"},
      {L("grid azimuth T = alpha - gamma + delta", "坐标方位角 T = α - γ + δ"), f.dir(c.grid_azimuth_rad.value, 2),
       f.sig(c.grid_azimuth_rad.sigma, 2), ""}};
  result.blocks.push_back(chain);
  return result;
}

CheckList check_list(const std::vector<gyro::Check>& list, const SheetLabels& L) {
  CheckList cl;
  cl.columns = {L("check", "检核项目"), L("value", "实测值"), L("limit", "限差"), L("result", "结论"),
                L("source of the limit", "限差依据")};
  cl.verdicts = {L("PASS", "合格"), L("FAIL", "不合格"), L("no check applies", "无适用检核")};
  for (const auto& k : list) {
    const bool div = k.unit == gyro::CheckUnit::Div;
    const bool runs = k.unit == gyro::CheckUnit::Runs || k.unit == gyro::CheckUnit::Observers ||
                      k.unit == gyro::CheckUnit::Checks || k.unit == gyro::CheckUnit::Entries;
    const int dec = div ? 2 : runs ? 0 : 1;
    const bool seconds = k.unit == gyro::CheckUnit::Seconds;
    const std::string unit = div ? " div" : runs ? "" : seconds ? " s" : "\"";
    cl.checks.push_back({k.name, fmt::format("{:.{}f}{}", k.value, dec, unit),
                         fmt::format("{}{}{:.{}f}{}", k.minimum ? (L.zh ? "\u2265 " : "at least ") : "", k.signed_value ? "\u00b1" : "",
                                     k.tolerance, dec, unit),
                         k.pass, k.source});
  }
  return cl;
}

Section checks_section(const gyro::CampaignResult& r, const AngleFormat& f) {
  const SheetLabels L{r.input.record.language == "zh"};
  Section checks{"checks", L("Tolerance checks", "限差检核"), {}, 2};
  checks.blocks.push_back(check_list(r.checks, L));
  std::vector<KeyValue> m;
  if (r.constant_one_run_sigma_rad)
    m.push_back({L("instrument constant, one run (m = sqrt([vv]/(n-1)))", "仪器常数一测回中误差 (m = sqrt([vv]/(n-1)))"),
                 f.sig(*r.constant_one_run_sigma_rad, 1)});
  if (r.line_one_run_sigma_rad)
    m.push_back({L("gyro azimuth on the line, one run", "测线陀螺方位角一测回中误差"), f.sig(*r.line_one_run_sigma_rad, 1)});
  if (!m.empty()) checks.blocks.push_back(KeyValueList{L("One-run standard deviations", "一测回中误差"), m});
  return checks;
}

// E from each determination on the known line, before and after.
Section calibration_section(const gyro::KnownLineInput& k, const gyro::CampaignResult& r, const AngleFormat& f) {
  Section cal{"calibration", "Calibration on the known line", {}, 2};
  cal.blocks.push_back(KeyValueList{
      "",
      {{"known azimuth given", fmt::format("{} ({})", f.dir(k.azimuth.value_rad.value, 2), geodesy::to_string(k.azimuth.kind))},
       {"known astronomic azimuth used",
        f.dir(r.known_astronomic_azimuth_rad->value, 2) + "  sigma " + f.sig(r.known_astronomic_azimuth_rad->sigma, 1)}}});
  Table t;
  t.columns = {"when", "label", "method", "stochastic model", "N_G", "sigma", "A_G", "E", "sigma E"};
  t.numeric = {false, false, false, false, true, true, true, true, true};
  std::vector<std::string> labels;
  std::vector<gyro::Uncertain> es;
  auto rows = [&](const char* when, const std::vector<gyro::DeterminationResult>& d,
                  const std::vector<gyro::Uncertain>& ag, const std::vector<gyro::Uncertain>& e) {
    for (std::size_t i = 0; i < d.size(); ++i) {
      t.rows.push_back({when, d[i].label, gyro::to_string(d[i].primary.method), stochastic_cell(d[i].stochastic),
                        f.dir(d[i].primary.north.north_rad, 2),
                        f.sig(d[i].primary.north.sigma_rad, 1), f.dir(ag[i].value, 2), f.sec(e[i].value, 2), f.sig(e[i].sigma, 1)});
      labels.push_back(d[i].label.empty() ? std::string(when) + " " + label_of(d[i], i) : d[i].label);
      es.push_back(e[i]);
    }
  };
  rows("before", r.known_before, r.known_gyro_azimuths_before, r.instrument_constant->before);
  rows("after", r.known_after, r.known_gyro_azimuths_after, r.instrument_constant->after);
  t.note = fmt::format("E = A_known - A_G. Mean E = {} (sigma {}).", f.sec(r.instrument_constant->mean.value, 2),
                       f.sig(r.instrument_constant->mean.sigma, 2));
  cal.blocks.push_back(t);
  cal.blocks.push_back(spread_plot("Instrument constant per determination", labels, es, r.instrument_constant->mean.value,
                                   r.instrument_constant->mean.sigma, "E minus mean E (arcsec)",
                                   "Points: E of each determination with +-1 sigma; band: sigma of the mean E."));
  return cal;
}

// The determinations on the unknown line and their gyro azimuths.
Section line_section(const gyro::CampaignInput& in, const gyro::CampaignResult& r, const AngleFormat& f) {
  Section line{"line", "Determinations on the line " + line_name(r), {}, 2};
  Table t;
  t.columns = {"#", "label", "mode", "method", "stochastic model", "N_G", "sigma", "target reading", "A_G", "sigma A_G"};
  t.numeric = {true, false, false, false, false, true, true, true, true, true};
  std::vector<std::string> labels;
  for (std::size_t i = 0; i < r.determinations.size(); ++i) {
    const auto& d = r.determinations[i];
    const auto& din = in.line.determinations[i];
    t.rows.push_back({std::to_string(i + 1), d.label, gyro::to_string(d.mode), gyro::to_string(d.primary.method),
                      stochastic_cell(d.stochastic), f.dir(d.primary.north.north_rad, 2), f.sig(d.primary.north.sigma_rad, 1),
                      din.target_reading_rad ? f.dir(din.target_reading_rad->value, 1) : "",
                      f.dir(r.gyro_azimuths[i].value, 2), f.sig(r.gyro_azimuths[i].sigma, 1)});
    labels.push_back(label_of(d, i));
  }
  t.note = fmt::format("Mean A_G = {}; sigma propagated {}, empirical {}; the larger is used.",
                       f.dir(r.gyro_azimuth_mean.mean.value, 2), f.sig(r.gyro_azimuth_mean.sigma_propagated, 2),
                       f.sig(r.gyro_azimuth_mean.sigma_empirical, 2));
  line.blocks.push_back(t);
  line.blocks.push_back(spread_plot("Gyro azimuth per determination", labels, r.gyro_azimuths,
                                    r.gyro_azimuth_mean.mean.value, r.gyro_azimuth_mean.mean.sigma,
                                    "A_G minus mean A_G (arcsec)",
                                    "Points: A_G of each determination with +-1 sigma; band: sigma of the mean."));
  return line;
}

// One level-3 section per determination, in detail.
void add_detail_sections(std::vector<Section>& out, const std::string& prefix, const std::string& title,
                         const std::vector<gyro::DeterminationInput>& ins,
                         const std::vector<gyro::DeterminationResult>& res, const gyro::Instrument& inst,
                         const AngleFormat& f) {
  for (std::size_t i = 0; i < res.size(); ++i)
    out.push_back(Section{fmt::format("{}-{}", prefix, i + 1), fmt::format("{} {}: {}", title, i + 1, label_of(res[i], i)),
                          determination_blocks(ins[i], res[i], inst, f), 3});
}

Section notes_section(const gyro::CampaignResult& r) {
  Section notes{"notes", "Notes and warnings", {}, 2};
  notes.blocks.push_back(Notes{"Warnings", r.warnings, true});
  notes.blocks.push_back(Notes{"Notes", r.notes, false});
  if (r.warnings.empty()) notes.blocks.push_back(Paragraph{"No warnings."});
  return notes;
}

}  // namespace

Document gyro_reduce_document(const gyro::ReduceResult& r) {
  const gyro::ReduceInput& in = r.input;
  const std::string& file = in.file;
  const AngleFormat f(in.angle_unit);
  Document doc;
  doc.title = "Gyro-theodolite determinations";
  doc.subtitle = file;
  doc.footer = report_generator();
  doc.header.push_back({"input file", file});
  doc.header.push_back({"station latitude", format_dms(Angle::radians(in.latitude_rad), {2, true, false})});
  const gyro::Instrument& inst = r.instrument.instrument;
  gyro::InstrumentSpec spec_view;  // instrument constants as resolved
  spec_view.scale_value_rad = inst.scale_value_rad;
  spec_view.sigma_time_s = inst.sigma_time_s;
  spec_view.sigma_reading_div = inst.sigma_reading_div;
  for (auto& kv : instrument_header(spec_view, inst))
    if (kv.key != "accuracy class") doc.header.push_back(kv);
  doc.sections.push_back(reduce_summary_section(r, f));
  for (std::size_t i = 0; i < r.determinations.size(); ++i) {
    const auto& d = r.determinations[i];
    doc.sections.push_back(Section{fmt::format("determination-{}", i + 1),
                                   fmt::format("Determination {}{}", i + 1, d.label.empty() ? "" : ": " + d.label),
                                   determination_blocks(in.determinations[i], d, r.instrument.instrument, f), 2});
  }
  return doc;
}

Document gyro_campaign_document(const gyro::CampaignResult& r) {
  const gyro::CampaignInput& in = r.input;
  const std::string& file = in.file;
  const AngleFormat f(in.angle_unit);
  Document doc;
  doc.title = "Gyro orientation: " + (r.name.empty() ? std::string("campaign") : r.name);
  doc.subtitle = file;
  doc.footer = report_generator();
  doc.header.push_back({"input file", file});
  // The result sheet fills the first page; what it rests on follows it.
  Section inputs{"inputs", "Instrument, grid and stations", {}, 2};
  std::vector<KeyValue> kv = instrument_header(in.instrument, r.instrument_station.instrument);
  kv.push_back({"grid", geodesy::describe(in.grid)});
  kv.push_back({"station", point_text(r.station, f)});
  if (r.target) kv.push_back({"target", point_text(*r.target, f)});
  if (r.known_station) kv.push_back({"known station", point_text(*r.known_station, f)});
  if (r.known_target) kv.push_back({"known target", point_text(*r.known_target, f)});
  inputs.blocks.push_back(KeyValueList{"", kv});

  doc.sections.push_back(result_sheet_section(in, r, f));
  doc.sections.push_back(inputs);
  doc.sections.push_back(campaign_result_section(r, f));
  doc.sections.push_back(checks_section(r, f));
  if (r.instrument_constant && in.known_line) doc.sections.push_back(calibration_section(*in.known_line, r, f));
  doc.sections.push_back(line_section(in, r, f));
  if (in.known_line) {
    const gyro::Instrument& ik = r.instrument_known->instrument;
    add_detail_sections(doc.sections, "known-before", "Known line, before", in.known_line->before, r.known_before, ik, f);
    add_detail_sections(doc.sections, "known-after", "Known line, after", in.known_line->after, r.known_after, ik, f);
  }
  add_detail_sections(doc.sections, "line-determination", "Line", in.line.determinations, r.determinations,
                      r.instrument_station.instrument, f);
  doc.sections.push_back(notes_section(r));
  return doc;
}

Document gyro_orientations_document(const gyro::OrientationsResult& r, const std::vector<gyro::CampaignResult>& o) {
  if (o.size() != r.grid_azimuths_rad.size() || o.empty())
    throw InputError(fmt::format("the orientations report needs the {} campaign results combined, got {}",
                                 r.grid_azimuths_rad.size(), o.size()));
  const gyro::CampaignResult& first = o.front();
  const SheetLabels L{first.input.record.language == "zh"};
  const AngleFormat f(first.input.angle_unit);
  const std::string line = r.station + (r.target.empty() ? "" : " to " + r.target);
  Document doc;
  doc.title = "Independent gyro orientations: " + line;
  doc.subtitle = fmt::format("{} orientations", o.size());
  doc.footer = report_generator();
  for (std::size_t i = 0; i < r.files.size(); ++i) doc.header.push_back({fmt::format("orientation {}", i + 1), r.files[i]});

  Section s{"result-sheet", L("Result sheet of the independent orientations", "陀螺定向成果表 (独立定向)"), {}, 2};
  s.page_break_after = true;
  int failed = 0;
  for (const auto& k : r.checks) failed += k.pass ? 0 : 1;
  const std::string detail =
      failed == 0 ? fmt::format("{}: {}", L("all checks pass", "全部检核合格"), r.checks.size())
                  : fmt::format("{} OF {} CHECKS FAILED: do not use this azimuth before they are resolved{}", failed,
                                r.checks.size(), L.zh ? " (检核不合格, 不得使用)" : "");
  s.blocks.push_back(Highlight{L("Mean grid azimuth", "平均坐标方位角") + " " + line,
                               f.dir(r.mean.mean.value, 1) + "  \u00b1 " + f.sig(r.mean.mean.sigma, 1), detail,
                               failed > 0});
  std::vector<KeyValue> job;
  job.push_back({L("station", "测站") + " " + first.station.name,
                 fmt::format("{} {}, {} {}", L("latitude", "纬度"),
                             format_dms(Angle::radians(first.station.lat_rad), {2, true, false}), L("longitude", "经度"),
                             format_dms(Angle::radians(first.station.lon_rad), {2, true, false}))});
  for (const auto* p : {&first.station, first.target ? &*first.target : nullptr})
    if (p)
      job.push_back({L("coordinates of", "坐标") + " " + p->name,
                     fmt::format("x {:.3f} m, y {:.3f} m", p->grid.x_north_m, p->grid.y_east_m)});
  job.push_back({L("grid", "坐标系"), geodesy::describe(first.input.grid)});
  job.push_back({L("limits", "限差依据"), r.limits.source});
  s.blocks.push_back(KeyValueList{L("Line", "定向边"), job});

  Table t;
  t.title = L("Orientations", "各次定向");
  t.columns = {"#", L("date", "日期"), L("instrument", "仪器"), L("programme", "观测程序"), L("E used", "仪器常数 E"),
               L("grid azimuth T", "坐标方位角 T"), L("sigma", "中误差"), L("T minus mean", "与平均值之差"),
               L("own checks", "本次检核")};
  t.numeric = {true, false, false, false, true, true, true, true, false};
  for (std::size_t i = 0; i < o.size(); ++i) {
    const gyro::CampaignResult& c = o[i];
    const gyro::CampaignInput& in = c.input;
    const std::string programme = in.known_line ? fmt::format("{}-{}-{}", in.known_line->before.size(),
                                                              in.line.determinations.size(), in.known_line->after.size())
                                                : fmt::format("{} ({})", in.line.determinations.size(), L("E given", "E 给定"));
    t.rows.push_back({std::to_string(i + 1), in.record.date, in.instrument.name, programme,
                      f.sec(c.instrument_constant_used_rad.value, 1), f.dir(r.grid_azimuths_rad[i].value, 1),
                      f.sig(r.grid_azimuths_rad[i].sigma, 1),
                      f.sec(wrap_signed_rad(r.grid_azimuths_rad[i].value - r.mean.mean.value), 1),
                      c.all_checks_pass() ? L("pass", "合格") : L("FAILED", "不合格")});
  }
  s.blocks.push_back(t);

  Table m;
  m.title = L("Mean and its sigma", "平均值及其中误差");
  m.columns = {L("quantity", "项目"), L("value", "数值")};
  m.numeric = {false, true};
  m.rows.push_back({L("mean grid azimuth", "平均坐标方位角"), f.dir(r.mean.mean.value, 1)});
  m.rows.push_back({L("sigma of the mean (used)", "平均值中误差"), f.sig(r.mean.mean.sigma, 2)});
  m.rows.push_back({L("own parts, propagated", "各次独立部分 (传播)"), f.sig(r.sigma_own_propagated_rad, 2)});
  if (std::isfinite(r.mean.sigma_empirical))
    m.rows.push_back({L("from the scatter of the orientations", "由各次互差"), f.sig(r.mean.sigma_empirical, 2)});
  m.rows.push_back({L("shared parts (correlated)", "共同部分 (相关)"), f.sig(r.sigma_shared_rad, 2)});
  m.rows.push_back({L("as if independent (not used)", "按独立计算 (未用)"), f.sig(r.sigma_if_independent_rad, 2)});
  m.rows.push_back({L("largest difference of the orientations", "各次定向最大互差"), f.sec(r.mean.max_difference, 1)});
  if (first.line_grid_azimuth_from_coordinates_rad) {
    m.rows.push_back({L("azimuth of the coordinates (traverse)", "导线坐标方位角"),
                      f.dir(*first.line_grid_azimuth_from_coordinates_rad, 1)});
    m.rows.push_back({L("mean minus traverse azimuth", "平均陀螺方位角与导线方位角之差"),
                      f.sec(wrap_signed_rad(r.mean.mean.value - *first.line_grid_azimuth_from_coordinates_rad), 1)});
  }
  m.note = L("sigma = sqrt(max(own, scatter)^2 + shared^2): the scatter cannot show what the orientations share.",
             "中误差 = sqrt(max(独立部分, 互差)^2 + 共同部分^2)");
  s.blocks.push_back(m);
  {
    std::vector<std::string> labels;
    std::vector<Uncertain> values = r.grid_azimuths_rad;
    for (std::size_t i = 0; i < values.size(); ++i) labels.push_back(fmt::format("{} {}", L("orientation", "定向"), i + 1));
    if (first.line_grid_azimuth_from_coordinates_rad) {
      labels.push_back(L("traverse (coordinates)", "导线坐标"));
      values.push_back({*first.line_grid_azimuth_from_coordinates_rad, 0.0});
    }
    s.blocks.push_back(gyro_plots::spread_plot(
        L("Orientations about their mean", "各次定向与平均值"), labels, values, r.mean.mean.value, r.mean.mean.sigma,
        "T minus the mean (arcsec)", "Bars: +-1 sigma of each orientation; band: +-1 sigma of the mean."));
  }
  if (!r.shared_sources.empty())
    s.blocks.push_back(Notes{L("Shared by the orientations (correlated)", "各次定向共同的误差来源"), r.shared_sources, false});
  if (failed > 0) {
    std::vector<std::string> items;
    for (const auto& k : r.checks)
      if (!k.pass) items.push_back(check_text(k));
    s.blocks.push_back(Notes{L("Failed checks", "不合格检核"), items, true});
  }
  s.blocks.push_back(Signatures{{{L("computed by", "计算者"), first.input.record.computed_by},
                                 {L("checked by", "检查者"), first.input.record.checked_by}},
                                {L("name", "姓名"), L("signature", "签名"), L("date", "日期")}});
  doc.sections.push_back(s);

  Section checks{"checks", L("Tolerance checks", "限差检核"), {}, 2};
  checks.blocks.push_back(check_list(r.checks, L));
  doc.sections.push_back(checks);
  Section notes{"notes", L("Notes", "说明"), {}, 2};
  notes.blocks.push_back(Notes{"", r.notes, false});
  doc.sections.push_back(notes);
  return doc;
}

}  // namespace meridian::report
