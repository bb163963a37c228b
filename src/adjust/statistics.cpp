#include "meridian/adjust/statistics.hpp"

#include <cmath>
#include <exception>

#include <fmt/format.h>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>

#include "meridian/core/checks.hpp"
#include "meridian/core/error.hpp"

namespace meridian::adjust {
namespace {

namespace bm = boost::math;

void check_alpha(double alpha, const char* name = "significance level α") {
  if (!(alpha > 0.0 && alpha < 1.0))
    throw InputError(fmt::format("{} must be in (0, 1), is {}", name, alpha));
}

void check_dof(double dof, const char* name = "degrees of freedom") {
  if (!(std::isfinite(dof) && dof >= 1.0))
    throw InputError(fmt::format("{} must be finite and ≥ 1, is {}", name, dof));
}

void check_statistic(double x, const char* name) {
  if (!(std::isfinite(x) && x >= 0.0))
    throw InputError(fmt::format("{} must be finite and ≥ 0, is {}", name, x));
}

// Boost.Math reports its failures (overflow, no convergence) by exceptions; they become
// NumericalError, and so would a non-finite result.
template <typename F>
double evaluate(const char* what, F f) {
  double r = 0.0;
  try {
    r = f();
  } catch (const std::exception& e) {
    throw NumericalError(fmt::format("{}: {}", what, e.what()));
  }
  if (!std::isfinite(r)) throw NumericalError(fmt::format("{} is not finite ({})", what, r));
  return r;
}

// The distributions, with their parameters checked first (Boost would throw domain_error).
bm::chi_squared_distribution<double> chi_squared(double dof) {
  check_dof(dof);
  return bm::chi_squared_distribution<double>(dof);
}

bm::students_t_distribution<double> students_t(double dof) {
  check_dof(dof);
  return bm::students_t_distribution<double>(dof);
}

bm::fisher_f_distribution<double> fisher_f(double dof1, double dof2) {
  check_dof(dof1, "numerator degrees of freedom");
  check_dof(dof2, "denominator degrees of freedom");
  return bm::fisher_f_distribution<double>(dof1, dof2);
}

// x with P(X > x) = p.
template <typename Distribution>
double upper_quantile(const Distribution& d, double p, const char* what) {
  return evaluate(what, [&] { return bm::quantile(bm::complement(d, p)); });
}

// P(X > x).
template <typename Distribution>
double upper_probability(const Distribution& d, double x, const char* what) {
  return evaluate(what, [&] { return bm::cdf(bm::complement(d, x)); });
}

}  // namespace

// ---------------------------------------------------------------------------------------------

double chi_squared_upper_quantile(double alpha, double dof) {
  check_alpha(alpha);
  return upper_quantile(chi_squared(dof), alpha, "χ² quantile");
}

double chi_squared_upper_probability(double x, double dof) {
  check_statistic(x, "χ² statistic");
  return upper_probability(chi_squared(dof), x, "χ² tail probability");
}

double normal_two_sided_critical(double alpha) {
  check_alpha(alpha);
  return upper_quantile(bm::normal_distribution<double>(), 0.5 * alpha, "normal quantile");
}

double normal_two_sided_probability(double z) {
  require_finite(z, "normal statistic");
  return 2.0 * upper_probability(bm::normal_distribution<double>(), std::abs(z),
                                 "normal tail probability");
}

double student_t_two_sided_critical(double alpha, double dof) {
  check_alpha(alpha);
  return upper_quantile(students_t(dof), 0.5 * alpha, "Student t quantile");
}

double student_t_two_sided_probability(double t, double dof) {
  require_finite(t, "t statistic");
  return 2.0 * upper_probability(students_t(dof), std::abs(t), "Student t tail probability");
}

double fisher_f_upper_quantile(double alpha, double dof1, double dof2) {
  check_alpha(alpha);
  return upper_quantile(fisher_f(dof1, dof2), alpha, "F quantile");
}

double fisher_f_upper_probability(double x, double dof1, double dof2) {
  check_statistic(x, "F statistic");
  return upper_probability(fisher_f(dof1, dof2), x, "F tail probability");
}

// ---------------------------------------------------------------------------------------------

GlobalTestResult global_test(double vtpv, int dof, double alpha) {
  check_statistic(vtpv, "vᵀPv");
  if (dof < 1)
    throw InputError(
        fmt::format("the global test needs redundancy (degrees of freedom ≥ 1), has {}", dof));
  check_alpha(alpha);
  GlobalTestResult r;
  r.vtpv = vtpv;
  r.dof = dof;
  r.sigma0 = std::sqrt(vtpv / dof);
  r.alpha = alpha;
  r.critical_value = chi_squared_upper_quantile(alpha, dof);
  r.p_value = chi_squared_upper_probability(vtpv, dof);
  r.rejected = vtpv > r.critical_value;
  return r;
}

GlobalTestResult global_test(const LeastSquaresResult& result, double alpha) {
  return global_test(result.vtpv, result.dof, alpha);
}

bool chi_squared_gate(double statistic, double dof, double alpha) {
  check_statistic(statistic, "gated statistic");
  return statistic <= chi_squared_upper_quantile(alpha, dof);
}

// ---------------------------------------------------------------------------------------------

DataSnoopingResult w_test(const Eigen::VectorXd& w, double critical_value) {
  if (!(std::isfinite(critical_value) && critical_value > 0.0))
    throw InputError(
        fmt::format("w-test critical value must be positive and finite, is {}", critical_value));
  DataSnoopingResult r;
  r.critical_value = critical_value;
  r.alpha0 = normal_two_sided_probability(critical_value);
  for (Eigen::Index i = 0; i < w.size(); ++i) {
    const double wi = w(i);
    if (std::isnan(wi)) continue;  // not controlled
    if (std::isinf(wi)) throw InputError(fmt::format("w statistic of observation {} is {}", i, wi));
    ++r.tested;
    const int index = static_cast<int>(i);
    if (std::abs(wi) > critical_value) r.rejected.push_back(index);
    if (r.largest_index < 0 || std::abs(wi) > std::abs(r.largest_w)) {
      r.largest_index = index;
      r.largest_w = wi;
    }
  }
  return r;
}

DataSnoopingResult data_snooping(const LeastSquaresResult& result, double alpha0) {
  check_alpha(alpha0, "w-test significance level α0");
  return w_test(result.w_statistics, normal_two_sided_critical(alpha0));
}

}  // namespace meridian::adjust
