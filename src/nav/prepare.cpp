#include <algorithm>
#include <cmath>
#include <numeric>

#include <fmt/format.h>

#include "meridian/core/checks.hpp"
#include "meridian/core/error.hpp"
#include "prepared.hpp"

namespace meridian::nav::detail {

namespace {

[[noreturn]] void fail(const std::string& field, const std::string& message) {
  throw InputError(message, {{}, {}, field});
}

std::string at(const char* list, std::size_t i, const char* member) {
  return fmt::format("{}[{}].{}", list, i, member);
}

// core's check (one message everywhere): "dr[3].time_s: the value is not finite (nan)".
void require_finite(double v, const std::string& field) { meridian::require_finite(v, "the value", field); }

bool is_covariance(const Eigen::Matrix2d& c, bool definite) {
  if (!c.allFinite()) return false;
  if (std::abs(c(0, 1) - c(1, 0)) > 1e-9 * c.cwiseAbs().maxCoeff()) return false;
  const double det = c(0, 0) * c(1, 1) - c(0, 1) * c(1, 0);
  if (definite) return c(0, 0) > 0.0 && det > 0.0;
  return c(0, 0) >= 0.0 && c(1, 1) >= 0.0 && det >= -1e-12 * c.cwiseAbs().maxCoeff();
}

// Reduce an observation at time `time` to its nearest epoch (spec §3). Returns nullopt with
// a reason when it cannot be reduced.
std::optional<Reduced> reduce(const Prepared& p, double time, double max_reduction_s,
                              std::string& reason) {
  const auto& t = p.t;
  if (time < t.front() - max_reduction_s || time > t.back() + max_reduction_s) {
    reason = fmt::format("time {:.3f} s is more than max_reduction_s ({:g} s) outside the "
                         "dead-reckoning span {:.3f} … {:.3f} s",
                         time, max_reduction_s, t.front(), t.back());
    return std::nullopt;
  }
  const auto it = std::lower_bound(t.begin(), t.end(), time);
  std::size_t k = static_cast<std::size_t>(it - t.begin());
  if (k == t.size()) k = t.size() - 1;
  if (k > 0 && std::abs(t[k - 1] - time) <= std::abs(t[k] - time)) --k;  // ties: earlier
  const double dt = time - t[k];
  if (std::abs(dt) > max_reduction_s) {
    reason = fmt::format("{:.1f} s from the nearest dead-reckoning epoch (max_reduction_s {:g})",
                         std::abs(dt), max_reduction_s);
    return std::nullopt;
  }
  Reduced r;
  r.epoch = k;
  r.dt_s = dt;
  if (dt != 0.0) {
    // The velocity of the interval that contains the observation time (spec §1: a sample's
    // velocity holds over the interval that ends at it).
    const std::size_t s = dt > 0.0 ? std::min(k + 1, t.size() - 1) : k;
    const DrIncrement d = dr_increment(p.input->dr[s], dt, p.input->options.sequential_sigma_velocity_m_s);
    r.delta = d.delta;
    r.q_delta = d.q;
    r.q_delta_seq = d.q_seq;
  }
  return r;
}

// The DR displacement from epoch 0 to `time` with its covariance under the white DR noise
// (q) and with the sequential methods' σ (q_seq): the increments of the epochs up to `time`
// and the part of the interval that contains it (before t₀: the first sample's velocity;
// after the last epoch: the last sample's), as reduce() moves an observation.
struct Displacement {
  Eigen::Vector2d d = Eigen::Vector2d::Zero();
  Eigen::Matrix2d q = Eigen::Matrix2d::Zero();
  Eigen::Matrix2d q_seq = Eigen::Matrix2d::Zero();
};
Displacement dr_displacement(const Prepared& p, double time) {
  Displacement out;
  const auto& dr = p.input->dr;
  const auto part = [&](double dt, const DrSample& s) {
    const DrIncrement i = dr_increment(s, dt, p.input->options.sequential_sigma_velocity_m_s);
    out.d += i.delta;
    out.q += i.q;
    out.q_seq += i.q_seq;
  };
  if (time < p.t[0]) {
    part(time - p.t[0], dr[0]);
    return out;
  }
  std::size_t k = 0;
  while (k + 1 < p.epochs && p.t[k + 1] <= time) {
    ++k;
    out.d += p.incr[k];
    out.q += p.q_incr[k];
    out.q_seq += p.q_incr_seq[k];
  }
  if (time > p.t[k]) part(time - p.t[k], dr[std::min(k + 1, p.epochs - 1)]);
  return out;
}

// The initial position's values, or the index of the fix that gives it.
void check_initial(const Input& in) {
  if (!in.initial_fix) {
    require_finite(in.initial.x_north_m, "initial.x_north_m");
    require_finite(in.initial.y_east_m, "initial.y_east_m");
    if (!(std::isfinite(in.initial.sigma_m) && in.initial.sigma_m > 0.0))
      fail("initial.sigma_m", "must be finite and > 0");
  } else if (*in.initial_fix >= in.fixes.size()) {
    fail("initial_fix", fmt::format("no fix {} (there are {})", *in.initial_fix, in.fixes.size()));
  }
}

// Epochs: one per DR sample, with the DR increment into each and the pure DR track from 0.
void build_epochs(Prepared& p, const Input& in) {
  const Options& o = in.options;
  const std::size_t n = in.dr.size();
  p.epochs = n;
  p.t.resize(n);
  p.dt.assign(n, 0.0);
  p.incr.assign(n, Eigen::Vector2d::Zero());
  p.q_incr.assign(n, Eigen::Matrix2d::Zero());
  p.q_incr_seq.assign(n, Eigen::Matrix2d::Zero());
  p.dr.assign(n, Eigen::Vector2d::Zero());  // from 0 here; the initial position is added later
  for (std::size_t k = 0; k < n; ++k) {
    const DrSample& d = in.dr[k];
    require_finite(d.time_s, at("dr", k, "time_s"));
    require_finite(d.v_north_m_s, at("dr", k, "v_north_m_s"));
    require_finite(d.v_east_m_s, at("dr", k, "v_east_m_s"));
    if (!is_covariance(d.covariance, false))
      fail(at("dr", k, "covariance"), "is not a symmetric covariance with variances >= 0");
    p.t[k] = d.time_s;
    if (k == 0) continue;
    const double dt = d.time_s - in.dr[k - 1].time_s;
    if (!(dt > 0.0))
      fail(at("dr", k, "time_s"),
           fmt::format("times must increase strictly: {:.6f} s after {:.6f} s", d.time_s,
                       in.dr[k - 1].time_s));
    if (dt > o.max_dr_gap_s)
      fail(at("dr", k, "time_s"),
           fmt::format("a gap of {:.1f} s in the dead reckoning exceeds max_dr_gap_s = {:g} s", dt,
                       o.max_dr_gap_s));
    const DrIncrement i = dr_increment(d, dt, o.sequential_sigma_velocity_m_s);
    p.dt[k] = dt;
    p.incr[k] = i.delta;
    p.q_incr[k] = i.q;
    p.q_incr_seq[k] = i.q_seq;
    p.dr[k] = p.dr[k - 1] + p.incr[k];
  }
}

// The statistics bins are allocated per line: bounded, whatever statistics_bin_s says.
void check_statistics_bins(const Prepared& p, const Options& o) {
  const double span = p.t.back() - p.t.front();
  if (span / o.statistics_bin_s + 1.0 > kMaxStatisticsBins)
    fail("options.statistics_bin_s",
         fmt::format("{:g} s makes {:.3g} bins of the error statistics over the line of {:g} s; at most "
                     "{:g} (statistics_bin_s >= {:.3g} s)",
                     o.statistics_bin_s, std::floor(span / o.statistics_bin_s) + 1.0, span,
                     kMaxStatisticsBins, span / (kMaxStatisticsBins - 1.0)));
}

// Chain parameters: their place among the parameters, names and prior σ.
void place_chain_parameters(Prepared& p, const Input& in) {
  p.scale_col.assign(in.chains.size(), -1);
  p.offset_col.assign(in.chains.size(), -1);
  for (std::size_t c = 0; c < in.chains.size(); ++c) {
    const Chain& ch = in.chains[c];
    if (ch.estimate_scale) {
      if (!(std::isfinite(ch.sigma_scale_prior) && ch.sigma_scale_prior > 0.0))
        fail(at("chains", c, "sigma_scale_prior"), "must be finite and > 0");
      p.scale_col[c] = p.n_params++;
      p.param_names.emplace_back("scale");
      p.param_chain.push_back(c);
      p.param_prior_sigma.push_back(ch.sigma_scale_prior);
    }
    if (ch.estimate_offset) {
      if (!(std::isfinite(ch.sigma_offset_prior_m) && ch.sigma_offset_prior_m > 0.0))
        fail(at("chains", c, "sigma_offset_prior_m"), "must be finite and > 0");
      p.offset_col[c] = p.n_params++;
      p.param_names.emplace_back("offset_m");
      p.param_chain.push_back(c);
      p.param_prior_sigma.push_back(ch.sigma_offset_prior_m);
    }
  }
}

// A LOP's values and the stations and chain it names.
void check_lop(const Input& in, std::size_t i) {
  const Lop& l = in.lops[i];
  require_finite(l.time_s, at("lops", i, "time_s"));
  require_finite(l.value_m, at("lops", i, "value_m"));
  if (!(std::isfinite(l.sigma_m) && l.sigma_m > 0.0)) fail(at("lops", i, "sigma_m"), "must be finite and > 0");
  if (l.station >= in.stations.size())
    fail(at("lops", i, "station"), fmt::format("no station {} (there are {})", l.station, in.stations.size()));
  if (l.type == LopType::RangeDifference) {
    if (l.station2 >= in.stations.size())
      fail(at("lops", i, "station2"), fmt::format("no station {} (there are {})", l.station2, in.stations.size()));
    if (l.station2 == l.station) fail(at("lops", i, "station2"), "a range difference needs two different stations");
  }
  if (l.chain != Lop::kNoChain && l.chain >= in.chains.size())
    fail(at("lops", i, "chain"), fmt::format("no chain {} (there are {})", l.chain, in.chains.size()));
}

void check_stations(const Input& in) {
  for (std::size_t i = 0; i < in.stations.size(); ++i) {
    require_finite(in.stations[i].x_north_m, at("stations", i, "x_north_m"));
    require_finite(in.stations[i].y_east_m, at("stations", i, "y_east_m"));
  }
}

// LOPs and fixes checked and reduced to their epochs (spec §3); the ones too far from every
// epoch skipped, the initial fix kept out of the observations.
void reduce_observations(Prepared& p, const Input& in) {
  const Options& o = in.options;
  for (std::size_t i = 0; i < in.lops.size(); ++i) {
    check_lop(in, i);
    std::string reason;
    auto r = reduce(p, in.lops[i].time_s, o.max_reduction_s, reason);
    if (!r) {
      p.skipped.push_back({RejectedObservation::Kind::Lop, i, in.lops[i].time_s, reason, {}});
      continue;
    }
    r->index = i;
    p.lops.push_back(*r);
  }
  for (std::size_t i = 0; i < in.fixes.size(); ++i) {
    const Fix& f = in.fixes[i];
    require_finite(f.time_s, at("fixes", i, "time_s"));
    require_finite(f.x_north_m, at("fixes", i, "x_north_m"));
    require_finite(f.y_east_m, at("fixes", i, "y_east_m"));
    if (!is_covariance(f.covariance, true))
      fail(at("fixes", i, "covariance"), "is not a symmetric positive definite covariance");
    std::string reason;
    auto r = reduce(p, f.time_s, o.max_reduction_s, reason);
    if (in.initial_fix && *in.initial_fix == i) {
      if (!r)
        fail(at("fixes", i, "time_s"), "the fix that gives the initial position cannot be moved to "
                                       "the first epoch: " + reason);
      continue;  // its information is the prior (initial_state)
    }
    if (!r) {
      p.skipped.push_back({RejectedObservation::Kind::Fix, i, f.time_s, reason, {}});
      continue;
    }
    r->index = i;
    p.fixes.push_back(*r);
  }
}

// The initial position: given, or the initial fix moved back by the DR to epoch 0; the pure
// DR track starts there.
void initial_state(Prepared& p, const Input& in) {
  if (in.initial_fix) {
    const Fix& f = in.fixes[*in.initial_fix];
    const Displacement d = dr_displacement(p, f.time_s);
    p.initial_x = Eigen::Vector2d(f.x_north_m, f.y_east_m) - d.d;
    p.initial_cov = f.covariance + d.q;
    p.initial_cov_seq = f.covariance + d.q_seq;
    p.initial_dt_s = f.time_s - p.t[0];
    p.skipped.push_back({RejectedObservation::Kind::Fix, *in.initial_fix, f.time_s,
                         fmt::format("gives the initial position (moved by the dead reckoning "
                                     "to the first epoch, t = {:.3f} s); not used again as an "
                                     "observation",
                                     p.t[0]),
                         {}});
  } else {
    p.initial_x = Eigen::Vector2d(in.initial.x_north_m, in.initial.y_east_m);
    p.initial_cov = p.initial_cov_seq = in.initial.sigma_m * in.initial.sigma_m * Eigen::Matrix2d::Identity();
  }
  for (Eigen::Vector2d& x : p.dr) x += p.initial_x;
}

// The reduced observations sorted by epoch, with the offsets of each epoch's.
void index_by_epoch(Prepared& p) {
  const auto by_epoch = [](const Reduced& a, const Reduced& b) {
    return a.epoch != b.epoch ? a.epoch < b.epoch : a.index < b.index;
  };
  std::sort(p.lops.begin(), p.lops.end(), by_epoch);
  std::sort(p.fixes.begin(), p.fixes.end(), by_epoch);
  const std::size_t n = p.epochs;
  const auto offsets = [n](const std::vector<Reduced>& v) {
    std::vector<std::size_t> b(n + 1, 0);
    for (const Reduced& r : v) ++b[r.epoch + 1];
    std::partial_sum(b.begin(), b.end(), b.begin());
    return b;
  };
  p.lop_begin = offsets(p.lops);
  p.fix_begin = offsets(p.fixes);
}

// Truth per epoch: linear interpolation between truth points at most kTruthMaxGap_s apart.
void truth_per_epoch(Prepared& p, const Input& in) {
  const std::size_t n = p.epochs;
  p.truth.assign(n, std::nullopt);
  const auto& tr = in.truth;
  for (std::size_t i = 0; i < tr.size(); ++i) {
    require_finite(tr[i].time_s, at("truth", i, "time_s"));
    require_finite(tr[i].x_north_m, at("truth", i, "x_north_m"));
    require_finite(tr[i].y_east_m, at("truth", i, "y_east_m"));
    if (i > 0 && !(tr[i].time_s > tr[i - 1].time_s)) fail(at("truth", i, "time_s"), "truth times must increase strictly");
  }
  if (tr.empty()) return;
  std::size_t j = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double tk = p.t[k];
    while (j + 1 < tr.size() && tr[j + 1].time_s <= tk) ++j;
    if (std::abs(tr[j].time_s - tk) <= 1e-6) {
      p.truth[k] = Eigen::Vector2d(tr[j].x_north_m, tr[j].y_east_m);
    } else if (tr[j].time_s < tk && j + 1 < tr.size() && tr[j + 1].time_s - tr[j].time_s <= kTruthMaxGap_s) {
      const double u = (tk - tr[j].time_s) / (tr[j + 1].time_s - tr[j].time_s);
      p.truth[k] = Eigen::Vector2d((1 - u) * tr[j].x_north_m + u * tr[j + 1].x_north_m,
                                   (1 - u) * tr[j].y_east_m + u * tr[j + 1].y_east_m);
    }
  }
}

}  // namespace

DrIncrement dr_increment(const DrSample& s, double dt, double sequential_sigma_velocity_m_s) {
  DrIncrement i;
  i.delta = dt * Eigen::Vector2d(s.v_north_m_s, s.v_east_m_s);
  i.q = dt * dt * s.covariance;
  const double sv2 = sequential_sigma_velocity_m_s * sequential_sigma_velocity_m_s;
  i.q_seq = i.q + dt * dt * sv2 * Eigen::Matrix2d::Identity();
  return i;
}

Prepared prepare(const Input& in) {
  validate(in.options);
  Prepared p;
  p.input = &in;
  if (in.dr.size() < 2) fail("dr", fmt::format("needs at least 2 dead-reckoning samples, got {}", in.dr.size()));
  check_initial(in);
  build_epochs(p, in);
  check_statistics_bins(p, in.options);
  check_stations(in);
  place_chain_parameters(p, in);
  reduce_observations(p, in);
  initial_state(p, in);
  index_by_epoch(p);
  truth_per_epoch(p, in);
  return p;
}

LopEvaluation evaluate_geometry(const Prepared& p, const Lop& lop, const Eigen::Vector2d& position,
                                const ChainValues& chain) {
  LopEvaluation e;
  const auto& st = p.input->stations;
  const auto unit = [&](std::size_t s, double& d) -> Eigen::RowVector2d {
    const Eigen::Vector2d v = position - Eigen::Vector2d(st[s].x_north_m, st[s].y_east_m);
    d = v.norm();
    if (d < kMinStationDistance_m) {
      e.ok = false;
      return Eigen::RowVector2d::Zero();
    }
    return (v / d).transpose();
  };
  double d1 = 0.0;
  Eigen::RowVector2d g = unit(lop.station, d1);
  double geometric = d1;
  if (lop.type == LopType::RangeDifference) {
    double d2 = 0.0;
    g -= unit(lop.station2, d2);
    geometric -= d2;
  }
  e.computed_m = (1.0 + chain.scale) * geometric + chain.offset;  // defined even at a station
  if (!e.ok) return e;
  e.h_position = (1.0 + chain.scale) * g;
  e.scale_state = chain.scale_state;
  e.h_scale = geometric;
  e.offset_state = chain.offset_state;
  return e;
}

}  // namespace meridian::nav::detail
