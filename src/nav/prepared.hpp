#pragma once
// The line as the methods see it (private to src/nav): epochs, DR increments, observations
// reduced to their epochs (spec §3), the state layout, and the evaluation of a LOP.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "meridian/nav/navigation.hpp"

namespace meridian::nav::detail {

/// An observation reduced to epoch `epoch`: the ship moves by `delta` (+ W·dt_s with a bias
/// W) from the epoch to the observation's time; `q_delta` is the DR covariance of that move.
struct Reduced {
  std::size_t index = 0;  ///< into Input::lops or Input::fixes
  std::size_t epoch = 0;
  double dt_s = 0.0;      ///< observation time − epoch time
  Eigen::Vector2d delta = Eigen::Vector2d::Zero();
  Eigen::Matrix2d q_delta = Eigen::Matrix2d::Zero();
  Eigen::Matrix2d q_delta_seq = Eigen::Matrix2d::Zero();  ///< with the sequential methods' σ
};

/// The dead-reckoning move of one sample's velocity over dt_s (spec §1; negative dt_s: back in
/// time): delta = dt·v, its covariance q = dt²·Σ_v under the sample's white noise, and q_seq =
/// q + dt²·σ_s²·I with σ_s = Options::sequential_sigma_velocity_m_s (the sequential methods).
/// The one home of the DR increment: epochs, reductions, the initial fix's displacement and
/// the dead-reckoned track of nav::to_plane.
struct DrIncrement {
  Eigen::Vector2d delta = Eigen::Vector2d::Zero();
  Eigen::Matrix2d q = Eigen::Matrix2d::Zero();
  Eigen::Matrix2d q_seq = Eigen::Matrix2d::Zero();
};
DrIncrement dr_increment(const DrSample& sample, double dt_s, double sequential_sigma_velocity_m_s);

/// Where the states sit in a state vector: position at 0, 1; bias (EKF) at `bias`, 2 states;
/// chain parameters from `params`.
struct Layout {
  int size = 2;
  int bias = -1;   ///< −1: no bias states
  int params = 2;  ///< first chain parameter
};

struct Prepared {
  const Input* input = nullptr;
  std::size_t epochs = 0;
  std::vector<double> t;                 ///< epoch times (s)
  std::vector<double> dt;                ///< t_k − t_{k−1} (0 at k = 0)
  std::vector<Eigen::Vector2d> incr;     ///< DR increment into epoch k (0 at k = 0)
  std::vector<Eigen::Matrix2d> q_incr;   ///< its covariance
  std::vector<Eigen::Matrix2d> q_incr_seq;  ///< with Options::sequential_sigma_velocity_m_s
  std::vector<Eigen::Vector2d> dr;       ///< pure DR position from the initial position
  /// The initial position at epoch 0 (Input::initial, or Input::initial_fix moved there) and
  /// its covariance under each DR model: the samples' white noise (dead reckoning, EKF) and
  /// with sequential_sigma_velocity_m_s (the sequential methods).
  Eigen::Vector2d initial_x = Eigen::Vector2d::Zero();
  Eigen::Matrix2d initial_cov = Eigen::Matrix2d::Zero();
  Eigen::Matrix2d initial_cov_seq = Eigen::Matrix2d::Zero();
  /// t_fix − t₀ of an initial fix (0 otherwise): the EKF's prior position depends on the bias
  /// by −initial_dt_s·W.
  double initial_dt_s = 0.0;
  std::vector<Reduced> lops;             ///< sorted by epoch
  std::vector<std::size_t> lop_begin;    ///< lops of epoch k: [lop_begin[k], lop_begin[k+1])
  std::vector<Reduced> fixes;            ///< sorted by epoch
  std::vector<std::size_t> fix_begin;
  std::vector<std::optional<Eigen::Vector2d>> truth;  ///< true position per epoch, when known
  int n_params = 0;
  std::vector<int> scale_col;   ///< per chain: parameter number (0-based among params) or −1
  std::vector<int> offset_col;
  std::vector<std::string> param_names;  ///< "scale" / "offset_m"
  std::vector<std::size_t> param_chain;
  std::vector<double> param_prior_sigma;
  std::vector<SkippedObservation> skipped;
  std::vector<std::string> notes;
  std::vector<std::string> warnings;
};

/// Validate the input and build the prepared line (throws InputError with field paths).
Prepared prepare(const Input& input);

/// A LOP's computed value and its partial derivatives at a ship position (spec §2).
struct LopEvaluation {
  bool ok = true;                  ///< false: the ship is within 1 m of a station
  double computed_m = 0.0;         ///< (1 + scale)·d + offset (also when not ok)
  Eigen::RowVector2d h_position = Eigen::RowVector2d::Zero();  ///< ∂L/∂(x, y)
  int scale_state = -1;            ///< state index of the chain's scale, or −1
  double h_scale = 0.0;            ///< ∂L/∂scale = d
  int offset_state = -1;           ///< state index of the chain's offset (∂L/∂offset = 1)
};

/// Evaluate LOP `lop` at position p with the chain parameters of `state` (layout).
template <typename State>
LopEvaluation evaluate_lop(const Prepared& p, const Lop& lop, const Eigen::Vector2d& position,
                           const State& state, const Layout& layout);

/// Chain parameter values of a state (a helper of evaluate_lop): scale, offset and their
/// state indices (−1 when not estimated).
struct ChainValues {
  double scale = 0.0;
  double offset = 0.0;
  int scale_state = -1;
  int offset_state = -1;
};
LopEvaluation evaluate_geometry(const Prepared& p, const Lop& lop, const Eigen::Vector2d& position,
                                const ChainValues& chain);

template <typename State>
LopEvaluation evaluate_lop(const Prepared& p, const Lop& lop, const Eigen::Vector2d& position,
                           const State& state, const Layout& layout) {
  ChainValues c;
  // Fixed-size states hold no chain parameters (process() uses them only when n_params = 0).
  if constexpr (State::RowsAtCompileTime == Eigen::Dynamic) {
  if (lop.chain != Lop::kNoChain) {
    const int sc = p.scale_col[lop.chain];
    const int oc = p.offset_col[lop.chain];
    if (sc >= 0) {
      c.scale_state = layout.params + sc;
      c.scale = state(c.scale_state);
    }
    if (oc >= 0) {
      c.offset_state = layout.params + oc;
      c.offset = state(c.offset_state);
    }
  }
  }
  return evaluate_geometry(p, lop, position, c);
}

}  // namespace meridian::nav::detail
