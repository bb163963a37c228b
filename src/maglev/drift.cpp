#include "meridian/maglev/drift.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "context.hpp"
#include "meridian/core/error.hpp"
#include "meridian/maglev/series_statistics.hpp"

namespace meridian::maglev {
using detail::at;

DriftModel drift_model_from_string(const std::string& name) {
  if (name == "none") return DriftModel::none;
  if (name == "linear") return DriftModel::linear;
  if (name == "quadratic") return DriftModel::quadratic;
  throw InputError(fmt::format("drift model \"{}\" (none, linear or quadratic)", name),
                   at("drift_model"));
}

const char* to_string(DriftModel m) {
  switch (m) {
    case DriftModel::none: return "none";
    case DriftModel::linear: return "linear";
    case DriftModel::quadratic: return "quadratic";
  }
  return "?";
}

int drift_order(DriftModel m) { return m == DriftModel::none ? 0 : m == DriftModel::linear ? 1 : 2; }

namespace {
// The median sample interval of both series (a gap of more than 10 of them starts a new block).
double median_interval(const PositionSeries& p1, const PositionSeries& p2) {
  std::vector<double> d;
  for (const auto* s : {&p1, &p2})
    for (std::size_t i = 1; i < s->time_s.size(); ++i) d.push_back(s->time_s[i] - s->time_s[i - 1]);
  if (d.empty()) return HUGE_VAL;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  return d[d.size() / 2];
}
}  // namespace

std::vector<TimeBlock> time_blocks(const PositionSeries& p1, const PositionSeries& p2) {
  std::vector<TimeBlock> b;
  const double gap = 10.0 * median_interval(p1, p2);
  const auto& t1 = p1.time_s;
  const auto& t2 = p2.time_s;
  std::size_t i = 0, j = 0;
  while (i < t1.size() || j < t2.size()) {
    if (i < t1.size() && j < t2.size() && t1[i] == t2[j]) return {};
    const bool one = j >= t2.size() || (i < t1.size() && t1[i] < t2[j]);
    TimeBlock k;
    k.position = one ? 1 : 2;
    std::size_t& c = one ? i : j;
    const auto& t = one ? t1 : t2;
    const auto& other = one ? t2 : t1;
    const std::size_t o = one ? j : i;
    k.begin = c;
    do ++c;
    while (c < t.size() && (o >= other.size() || t[c] < other[o]) && t[c] - t[c - 1] <= gap);
    k.end = c;
    k.begin_s = t[k.begin];
    k.end_s = t[k.end - 1];
    if (k.end - k.begin < 8 || b.size() >= 64) return {};
    b.push_back(k);
  }
  return b;
}

std::string block_sequence(const std::vector<TimeBlock>& blocks) {
  std::string s;
  for (const auto& b : blocks) s += (s.empty() ? "" : "-") + std::to_string(b.position);
  return s;
}

double LevelDriftFit::drift_at(double t_s) const {
  const double u = (t_s - reference_time_s) / half_span_s;
  double d = 0.0, p = u;
  for (int k = 0; k < order; ++k, p *= u) d += beta(2 + k) * p;
  return d;
}

Uncertain LevelDriftFit::rate_at(double t_s) const {
  if (order == 0) return {0.0, 0.0};
  const double u = (t_s - reference_time_s) / half_span_s;
  Eigen::VectorXd g = Eigen::VectorXd::Zero(beta.size());
  double p = 1.0;
  for (int k = 0; k < order; ++k, p *= u) g(2 + k) = (k + 1) * p / half_span_s;
  return {g.dot(beta), std::sqrt(std::max(0.0, g.dot(covariance * g)))};
}

namespace {

// The samples fitted, in time order: time, value, position.
struct Rows {
  std::vector<double> t, y;
  std::vector<int> pos;
};

Rows gather(const LevelDriftData& d) {
  Rows r;
  for (const TimeBlock& b : *d.blocks) {
    const PositionSeries& s = b.position == 1 ? *d.position1 : *d.position2;
    const auto v = b.position == 1 ? d.values1 : d.values2;
    const auto m = b.position == 1 ? d.mask1 : d.mask2;
    for (std::size_t i = b.begin; i < b.end; ++i) {
      if (!m[i]) continue;
      r.t.push_back(s.time_s[i]);
      r.y.push_back(v[i]);
      r.pos.push_back(b.position);
    }
  }
  return r;
}

void check(const LevelDriftData& d) {
  if (!d.position1 || !d.position2 || !d.blocks)
    throw InputError("the drift fit needs both positions and their blocks", at("drift"));
  if (d.values1.size() != d.position1->time_s.size() || d.mask1.size() != d.values1.size() ||
      d.values2.size() != d.position2->time_s.size() || d.mask2.size() != d.values2.size())
    throw InputError("the drift fit's values and masks do not match the series", at("drift"));
}

}  // namespace

LevelDriftFit fit_levels_and_drift(const LevelDriftData& data, int order) {
  check(data);
  const Rows rows = gather(data);
  const int p = 2 + order;
  const std::size_t n = rows.t.size();
  if (n < static_cast<std::size_t>(p) + 2)
    throw InputError(fmt::format("{} samples are too few for the drift fit", n), at("drift"));
  LevelDriftFit f;
  f.order = order;
  f.samples = n;
  double tsum = 0.0;
  for (double t : rows.t) tsum += t;
  f.reference_time_s = tsum / static_cast<double>(n);
  const auto [lo, hi] = std::minmax_element(rows.t.begin(), rows.t.end());
  f.half_span_s = std::max(0.5 * (*hi - *lo), 1e-9);
  // Normal equations: p ≤ 4 columns, accumulated without forming X.
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(p, p);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(p);
  Eigen::VectorXd x(p);
  auto row = [&](std::size_t j) {
    x.setZero();
    x(rows.pos[j] - 1) = 1.0;
    const double u = (rows.t[j] - f.reference_time_s) / f.half_span_s;
    double q = u;
    for (int k = 0; k < order; ++k, q *= u) x(2 + k) = q;
  };
  for (std::size_t j = 0; j < n; ++j) {
    row(j);
    N.selfadjointView<Eigen::Lower>().rankUpdate(x);
    rhs += x * rows.y[j];
  }
  N = N.selfadjointView<Eigen::Lower>();
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(N);
  const Eigen::MatrixXd Ninv = ldlt.solve(Eigen::MatrixXd::Identity(p, p));
  if (ldlt.info() != Eigen::Success || !Ninv.allFinite() || Ninv(0, 0) <= 0.0 ||
      Ninv(1, 1) <= 0.0 || (N * Ninv - Eigen::MatrixXd::Identity(p, p)).norm() > 1e-6)
    throw NumericalError("the levels and the drift cannot be separated (singular normal matrix)",
                         at("drift"));
  f.beta = Ninv * rhs;
  f.residuals_A.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    row(j);
    f.residuals_A[j] = rows.y[j] - x.dot(f.beta);
  }
  const MeanEstimate e = mean_with_autocorrelation(f.residuals_A);
  f.n_eff = e.n_eff;
  f.long_run_variance_A2 = e.variance * static_cast<double>(n) / e.n_eff;
  const double dof = e.n_eff > p + 1.0 ? e.n_eff / (e.n_eff - p) : static_cast<double>(p + 1);
  f.covariance = f.long_run_variance_A2 * dof * Ninv;
  // Δ without drift: 1/N_1 + 1/N_2.
  const double plain = 1.0 / N(0, 0) + 1.0 / N(1, 1);
  f.vif_difference = (Ninv(0, 0) + Ninv(1, 1) - 2.0 * Ninv(0, 1)) / plain;
  return f;
}

}  // namespace meridian::maglev
