#pragma once
// Helpers shared by the filter tests: error capture and scale-free differences.
#include <string>

#include <Eigen/Dense>

#include "meridian/core/error.hpp"

namespace meridian::filter::testing {

/// The error of type E thrown by f (what() and the context field), or empty strings.
struct Caught {
  bool thrown = false;
  std::string what;
  std::string field;
};
template <typename E, typename F>
Caught catch_error(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return {true, e.what(), e.context().field};
  }
  return {};
}

/// Largest |a_i − b_i|/σ_i with σ_i = sqrt(P_ii) of the reference: a state difference in
/// units of its own standard deviation.
template <typename A, typename B, typename C>
double state_difference(const A& a, const B& b, const C& P) {
  return ((a - b).array().abs() / P.diagonal().array().sqrt()).maxCoeff();
}

/// Largest |A_ij − B_ij|/(σ_i·σ_j), σ from the reference B: covariance differences relative to
/// the size of the entries they belong to (a correlation-scale difference).
template <typename A, typename B>
double covariance_difference(const A& a, const B& b) {
  const Eigen::VectorXd s = b.diagonal().array().sqrt();
  return ((a - b).array() / (s * s.transpose()).array()).abs().maxCoeff();
}

}  // namespace meridian::filter::testing
