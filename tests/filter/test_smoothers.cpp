// Smoothers: RTS and two-filter against the batch least-squares solution of the whole line
// (adjust::solve_linear), RTS against the two-filter smoother on the deflection model, the
// spill-to-disk path bit-identical to the in-memory path, the spill file's format and removal.
#include <unistd.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "example_models.hpp"
#include "meridian/adjust/least_squares.hpp"
#include "meridian/core/error.hpp"
#include "meridian/filter/kalman_filter.hpp"
#include "meridian/filter/rts_smoother.hpp"
#include "meridian/filter/smoother_storage.hpp"
#include "meridian/filter/two_filter_smoother.hpp"
#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;
using meridian::InputError;
using meridian::IoError;
using meridian::NumericalError;
using meridian::filter::BackwardInformationFilter;
using meridian::filter::DiscreteModel;
using meridian::filter::EpochRecord;
using meridian::filter::Estimate;
using meridian::filter::KalmanFilter;
using meridian::filter::Matrix;
using meridian::filter::rts_smooth;
using meridian::filter::SmootherStorage;
using meridian::filter::StorageOptions;
using meridian::filter::two_filter_smooth;
using meridian::filter::Vector;
using meridian::filter::testing::catch_error;
using meridian::filter::testing::covariance_difference;
using meridian::filter::testing::state_difference;
using namespace meridian::filter::examples;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

// A simulated line: per epoch the step into it (Φ_k, Q_k; unused at k = 0) and one observation.
template <int N, int M>
struct Line {
  Estimate<N> initial;
  std::vector<DiscreteModel<N>> steps;
  std::vector<Vector<M>> z;
  Matrix<M, N> H;
  Matrix<M, M> R;
  Index size() const { return static_cast<Index>(z.size()); }
};

template <int N, int M>
void simulate(Line<N, M>& line, Index epochs, const std::vector<double>& dts,
              const std::function<DiscreteModel<N>(double)>& discretise_step, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Vector<N> truth = line.initial.x + draw<N>(line.initial.P, rng);
  for (Index k = 0; k < epochs; ++k) {
    DiscreteModel<N> step{Matrix<N, N>::Identity(), Matrix<N, N>::Zero()};
    if (k > 0) {
      step = discretise_step(dts[static_cast<std::size_t>(k) % dts.size()]);
      truth = step.phi * truth + draw<N>(step.q, rng);
    }
    line.steps.push_back(step);
    line.z.push_back(line.H * truth + draw<M>(line.R, rng));
  }
}

// Forward filter over the line into `storage`: full records (P⁻ stored), or compact ones
// (append(filter): P⁻ recomputed when read back).
template <int N, int M>
void forward(const Line<N, M>& line, SmootherStorage<N>& storage, bool compact = false,
             const meridian::filter::TransitionKernel<N>* kernel = nullptr) {
  KalmanFilter<N> kf(line.initial);
  kf.set_transition_kernel(kernel);
  for (Index k = 0; k < line.size(); ++k) {
    const auto i = static_cast<std::size_t>(k);
    if (k > 0) kf.predict(line.steps[i]);
    kf.update(line.z[i], line.H, line.R);
    if (compact)
      storage.append(kf);
    else
      storage.append(kf.predicted(), kf.transition(), kf.estimate());
  }
}

template <int N, int M>
std::vector<Estimate<N>> two_filter(const Line<N, M>& line, SmootherStorage<N>& storage) {
  std::vector<Estimate<N>> out(static_cast<std::size_t>(line.size()));
  two_filter_smooth(
      storage,
      [&](Index k, BackwardInformationFilter<N>& back) {
        const auto i = static_cast<std::size_t>(k);
        back.update(line.z[i], line.H, line.R);
        if (k > 0) back.predict(line.steps[i].phi, line.steps[i].q);
      },
      [&](Index k, const Estimate<N>& e) { out[static_cast<std::size_t>(k)] = e; });
  return out;
}

// 2-D constant velocity, uneven steps, correlated position errors.
Line<CvState::size, 2> cv_line(Index epochs, std::uint64_t seed) {
  Line<CvState::size, 2> line;
  line.initial = {Vector<CvState::size>(100.0, -50.0, 3.0, -1.0),
                  Vector<CvState::size>(400.0, 400.0, 4.0, 4.0).asDiagonal()};
  line.H = cv_position_matrix();
  line.R << 25.0, 10.0, 10.0, 16.0;
  const auto model = cv_model(0.05);
  simulate<CvState::size, 2>(
      line, epochs, {1.0, 0.5, 2.0, 1.5},
      [&](double dt) { return meridian::filter::discretise(model, dt); }, seed);
  return line;
}

Line<DovState::size, 2> dov_line(Index epochs, std::uint64_t seed) {
  const DovParameters p;
  Line<DovState::size, 2> line;
  line.initial = dov_initial(p);
  line.H = dov_observation_matrix();
  line.R = dov_observation_covariance(p);
  const auto d = meridian::filter::discretise(dov_model(p), 1.0);
  simulate<DovState::size, 2>(
      line, epochs, {1.0}, [&](double) { return d; }, seed);
  return line;
}

// The whole line as one least-squares problem: prior x_0 = x̂_0 (P_0), process equations
// 0 = x_k − Φ_k·x_{k−1} − w_k (Q_k), observations z_k = H·x_k + v_k (R). Unknowns x_0…x_{K−1}.
template <int N, int M>
meridian::adjust::LeastSquaresResult batch(const Line<N, M>& line) {
  const Index K = line.size();
  const Index rows = N + (K - 1) * N + K * M;
  MatrixXd A = MatrixXd::Zero(rows, N * K);
  VectorXd l = VectorXd::Zero(rows);
  MatrixXd sigma = MatrixXd::Zero(rows, rows);
  Index r = 0;
  A.block(r, 0, N, N).setIdentity();
  l.segment(r, N) = line.initial.x;
  sigma.block(r, r, N, N) = line.initial.P;
  r += N;
  for (Index k = 1; k < K; ++k) {
    const auto& s = line.steps[static_cast<std::size_t>(k)];
    A.block(r, (k - 1) * N, N, N) = -s.phi;
    A.block(r, k * N, N, N).setIdentity();
    sigma.block(r, r, N, N) = s.q;
    r += N;
  }
  for (Index k = 0; k < K; ++k) {
    A.block(r, k * N, M, N) = line.H;
    l.segment(r, M) = line.z[static_cast<std::size_t>(k)];
    sigma.block(r, r, M, M) = line.R;
    r += M;
  }
  return meridian::adjust::solve_linear(A, l, sigma);
}

TEST(Smoothers, RtsAndTwoFilterEqualTheBatchLeastSquaresSolution) {
  const auto line = cv_line(40, 21);
  SmootherStorage<CvState::size> storage;
  forward(line, storage);
  const auto rts = rts_smooth(storage);
  const auto tf = two_filter(line, storage);
  const auto ls = batch(line);
  constexpr int n = CvState::size;
  double dx_rts = 0.0, dp_rts = 0.0, dx_tf = 0.0, dp_tf = 0.0;
  for (Index k = 0; k < line.size(); ++k) {
    const auto i = static_cast<std::size_t>(k);
    const VectorXd x = ls.x.segment(k * n, n);
    const MatrixXd P = ls.cofactor.block(k * n, k * n, n, n);
    dx_rts = std::max(dx_rts, state_difference(VectorXd(rts[i].x), x, P));
    dp_rts = std::max(dp_rts, covariance_difference(MatrixXd(rts[i].P), P));
    dx_tf = std::max(dx_tf, state_difference(VectorXd(tf[i].x), x, P));
    dp_tf = std::max(dp_tf, covariance_difference(MatrixXd(tf[i].P), P));
  }
  EXPECT_LT(dx_rts, 1e-9);
  EXPECT_LT(dp_rts, 1e-9);
  EXPECT_LT(dx_tf, 1e-9);
  EXPECT_LT(dp_tf, 1e-9);
  RecordProperty("rts_state_vs_batch", std::to_string(dx_rts));
  RecordProperty("rts_covariance_vs_batch", std::to_string(dp_rts));
  RecordProperty("two_filter_state_vs_batch", std::to_string(dx_tf));
  RecordProperty("two_filter_covariance_vs_batch", std::to_string(dp_tf));
}

TEST(Smoothers, RtsAndTwoFilterAgreeOnTheDeflectionModel) {
  const auto line = dov_line(600, 22);
  SmootherStorage<DovState::size> storage;
  forward(line, storage);
  const auto rts = rts_smooth(storage);
  const auto tf = two_filter(line, storage);
  double dx = 0.0, dp = 0.0;
  for (std::size_t i = 0; i < rts.size(); ++i) {
    dx = std::max(dx, state_difference(tf[i].x, rts[i].x, rts[i].P));
    dp = std::max(dp, covariance_difference(tf[i].P, rts[i].P));
  }
  EXPECT_LT(dx, 1e-9);
  EXPECT_LT(dp, 1e-9);
  RecordProperty("two_filter_vs_rts_state", std::to_string(dx));
  RecordProperty("two_filter_vs_rts_covariance", std::to_string(dp));
  // Smoothing helps: σ(δη) smoothed mid-line below the filtered one.
  KalmanFilter<DovState::size> kf(line.initial);
  for (Index k = 0; k <= 300; ++k) {
    if (k > 0) kf.predict(line.steps[static_cast<std::size_t>(k)]);
    kf.update(line.z[static_cast<std::size_t>(k)], line.H, line.R);
  }
  EXPECT_LT(rts[300].sigma(DovState::delta_eta), kf.estimate().sigma(DovState::delta_eta));
}

TEST(Smoothers, DynamicSizeEqualsFixedSize) {
  const auto line = cv_line(30, 23);
  Line<Eigen::Dynamic, Eigen::Dynamic> dyn;
  dyn.initial = {line.initial.x, line.initial.P};
  dyn.H = line.H;
  dyn.R = line.R;
  for (std::size_t i = 0; i < line.z.size(); ++i) {
    dyn.steps.push_back({line.steps[i].phi, line.steps[i].q});
    dyn.z.push_back(line.z[i]);
  }
  SmootherStorage<CvState::size> fixed_storage;
  SmootherStorage<Eigen::Dynamic> dyn_storage(CvState::size);
  forward(line, fixed_storage);
  forward(dyn, dyn_storage);
  const auto a = rts_smooth(fixed_storage);
  const auto b = rts_smooth(dyn_storage);
  const auto c = two_filter(dyn, dyn_storage);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_LT(state_difference(VectorXd(a[i].x), b[i].x, b[i].P), 1e-12) << i;
    EXPECT_LT(covariance_difference(MatrixXd(a[i].P), b[i].P), 1e-12) << i;
    EXPECT_LT(state_difference(c[i].x, b[i].x, b[i].P), 1e-9) << i;
  }
}

// Private scratch directory, removed at the end.
struct ScratchDir {
  fs::path path;
  ScratchDir() {
    path = fs::temp_directory_path() / ("meridian-filter-test-" + std::to_string(::getpid()));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~ScratchDir() { fs::remove_all(path); }
  bool empty() const { return fs::is_empty(path); }
};

template <int N>
bool bit_identical(const std::vector<Estimate<N>>& a, const std::vector<Estimate<N>>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::memcmp(a[i].x.data(), b[i].x.data(), sizeof(double) * N) != 0 ||
        std::memcmp(a[i].P.data(), b[i].P.data(), sizeof(double) * N * N) != 0)
      return false;
  return true;
}

TEST(SmootherStorage, SpillPathIsBitIdenticalToMemory) {
  const ScratchDir dir;
  const auto line = dov_line(2000, 24);
  constexpr int n = DovState::size;
  const std::size_t record_bytes = SmootherStorage<n>::record_doubles(n) * sizeof(double);
  EXPECT_EQ(record_bytes, 712u);  // index of Φ, x̂⁻, upper P⁻, x̂, upper P

  SmootherStorage<n> memory(n, {std::numeric_limits<std::size_t>::max(), dir.path, 1 << 20});
  // Spilled from the first record, with a 7-record buffer: many block boundaries.
  SmootherStorage<n> spilled(n, {0, dir.path, 7 * record_bytes});
  // 500 records in memory first, then spilled.
  SmootherStorage<n> midway(n, {500 * record_bytes, dir.path, 64 << 10});
  forward(line, memory);
  forward(line, spilled);
  forward(line, midway);
  EXPECT_FALSE(memory.spilled());
  EXPECT_TRUE(spilled.spilled());
  EXPECT_TRUE(midway.spilled());
  // A constant Φ is stored once (plus the identity of epoch 0).
  EXPECT_EQ(spilled.transitions(), 2);
  EXPECT_EQ(spilled.file_bytes(), 32u + 2000u * record_bytes + 32u + 2u * 64u * 8u);
  EXPECT_TRUE(dir.empty());  // anonymous: no name on disk even while in use

  const auto a = rts_smooth(memory);
  const auto b = rts_smooth(spilled);
  const auto c = rts_smooth(midway);
  EXPECT_TRUE(bit_identical(a, b));
  EXPECT_TRUE(bit_identical(a, c));
  // A Φ that changes at every epoch (an extended filter's Jacobian): one transition per epoch,
  // spilled on their own, still bit-identical.
  SmootherStorage<n> memory_varying(n,
                                    {std::numeric_limits<std::size_t>::max(), dir.path, 1 << 20});
  SmootherStorage<n> spilled_varying(n, {0, dir.path, 5 * record_bytes});
  for (auto* s : {&memory_varying, &spilled_varying}) {
    KalmanFilter<n> kf(line.initial);
    for (Index k = 0; k < 300; ++k) {
      const auto i = static_cast<std::size_t>(k);
      if (k > 0)
        kf.predict((1.0 + 1e-9 * static_cast<double>(k)) * line.steps[i].phi, line.steps[i].q);
      kf.update(line.z[i], line.H, line.R);
      s->append(kf.predicted(), kf.transition(), kf.estimate());
    }
  }
  EXPECT_EQ(spilled_varying.transitions(), 300);
  EXPECT_TRUE(bit_identical(rts_smooth(memory_varying), rts_smooth(spilled_varying)));
  EXPECT_TRUE(bit_identical(two_filter(line, memory), two_filter(line, spilled)));
  // A second pass over the same storage reads the same records.
  EXPECT_TRUE(bit_identical(a, rts_smooth(spilled)));
}

TEST(SmootherStorage, CompactRecordsGiveTheFullRecordsResultsBitForBit) {
  const ScratchDir dir;
  const auto line = dov_line(2000, 27);
  constexpr int n = DovState::size;
  const std::size_t compact_bytes = SmootherStorage<n>::compact_record_doubles(n) * sizeof(double);
  EXPECT_EQ(compact_bytes, 424u);  // index of Φ, x̂⁻, x̂, upper P
  constexpr std::size_t never = std::numeric_limits<std::size_t>::max();

  SmootherStorage<n> full(n, {never, dir.path, 1 << 20});
  SmootherStorage<n> memory(n, {never, dir.path, 1 << 20});
  SmootherStorage<n> spilled(n, {0, dir.path, 7 * compact_bytes});
  SmootherStorage<n> midway(n, {500 * compact_bytes, dir.path, 64 << 10});
  forward(line, full);
  forward(line, memory, true);
  forward(line, spilled, true);
  forward(line, midway, true);
  EXPECT_FALSE(full.compact());
  EXPECT_TRUE(memory.compact());
  EXPECT_FALSE(memory.spilled());
  EXPECT_TRUE(spilled.spilled());
  EXPECT_TRUE(midway.spilled());
  // Φ and Q_d constant: the identity and zero of epoch 0, then the line's (Φ, Q_d), 2·64 doubles.
  EXPECT_EQ(spilled.transitions(), 2);
  EXPECT_EQ(spilled.file_bytes(), 32u + 2000u * compact_bytes + 32u + 2u * 128u * 8u);

  const auto a = rts_smooth(full);
  EXPECT_TRUE(bit_identical(a, rts_smooth(memory)));
  EXPECT_TRUE(bit_identical(a, rts_smooth(spilled)));
  EXPECT_TRUE(bit_identical(a, rts_smooth(midway)));
  EXPECT_TRUE(bit_identical(a, rts_smooth(spilled)));  // a second pass
  EXPECT_TRUE(bit_identical(two_filter(line, full), two_filter(line, spilled)));
  // The reader gives back the forward pass's P⁻ bit for bit, not only the smoothed results.
  {
    auto rf = full.read_reverse();
    auto rc = spilled.read_reverse();
    EpochRecord<n> x, y;
    Index epochs = 0;
    while (rf.next(x)) {
      ASSERT_TRUE(rc.next(y));
      ASSERT_EQ(rf.index(), rc.index());
      EXPECT_EQ(std::memcmp(x.predicted.P.data(), y.predicted.P.data(), sizeof x.predicted.P), 0)
          << rf.index();
      EXPECT_EQ(std::memcmp(x.predicted.x.data(), y.predicted.x.data(), sizeof x.predicted.x), 0);
      EXPECT_EQ(std::memcmp(x.phi.data(), y.phi.data(), sizeof x.phi), 0);
      ++epochs;
    }
    EXPECT_FALSE(rc.next(y));
    EXPECT_EQ(epochs, 2000);
  }

  // Φ and Q_d changing at every epoch (an extended filter; a re-discretised model): one
  // transition per epoch, still bit-identical, in memory and spilled.
  SmootherStorage<n> full_varying(n, {never, dir.path, 1 << 20});
  SmootherStorage<n> spilled_varying(n, {0, dir.path, 5 * compact_bytes});
  for (auto* s : {&full_varying, &spilled_varying}) {
    KalmanFilter<n> kf(line.initial);
    for (Index k = 0; k < 300; ++k) {
      const auto i = static_cast<std::size_t>(k);
      const double f = 1.0 + 1e-9 * static_cast<double>(k);
      if (k > 0) kf.predict(f * line.steps[i].phi, (2.0 - f) * line.steps[i].q);
      kf.update(line.z[i], line.H, line.R);
      if (s == &full_varying)
        s->append(kf.predicted(), kf.transition(), kf.estimate());
      else
        s->append(kf);
    }
  }
  EXPECT_EQ(spilled_varying.transitions(), 300);
  EXPECT_TRUE(bit_identical(rts_smooth(full_varying), rts_smooth(spilled_varying)));

  // Dynamic sizes: the same operations as the dynamic filter's predict.
  const auto cv = cv_line(30, 28);
  Line<Eigen::Dynamic, Eigen::Dynamic> dyn;
  dyn.initial = {cv.initial.x, cv.initial.P};
  dyn.H = cv.H;
  dyn.R = cv.R;
  for (std::size_t i = 0; i < cv.z.size(); ++i) {
    dyn.steps.push_back({cv.steps[i].phi, cv.steps[i].q});
    dyn.z.push_back(cv.z[i]);
  }
  SmootherStorage<Eigen::Dynamic> dyn_full(CvState::size);
  SmootherStorage<Eigen::Dynamic> dyn_compact(CvState::size, {0, dir.path, 1 << 20});
  forward(dyn, dyn_full);
  forward(dyn, dyn_compact, true);
  const auto df = rts_smooth(dyn_full);
  const auto dc = rts_smooth(dyn_compact);
  ASSERT_EQ(df.size(), dc.size());
  for (std::size_t i = 0; i < df.size(); ++i) {
    EXPECT_TRUE(df[i].x == dc[i].x) << i;
    EXPECT_TRUE(df[i].P == dc[i].P) << i;
  }
  EXPECT_TRUE(dir.empty());
}

// The deflection model's structure: the attitude block with ε_U, and the two Gauss–Markov pairs.
constexpr std::array<std::uint32_t, DovState::size> dov_structure() {
  std::array<std::uint32_t, DovState::size> rows{};
  for (int j : {DovState::phi_e, DovState::phi_n, DovState::phi_u})
    rows[static_cast<std::size_t>(j)] = 0x0fu;
  rows[DovState::eps_u] = 1u << DovState::eps_u;
  rows[DovState::x_e] = rows[DovState::delta_eta] = (1u << DovState::x_e) | (1u << DovState::delta_eta);
  rows[DovState::x_n] = rows[DovState::delta_xi] = (1u << DovState::x_n) | (1u << DovState::delta_xi);
  return rows;
}
constexpr meridian::filter::TransitionKernel<DovState::size> kDovKernel =
    meridian::filter::structured_transition_kernel<DovState::size, dov_structure()>();

TEST(StructuredTransition, GivesTheGenericKernelsNumbersBitForBit) {
  constexpr int n = DovState::size;
  using meridian::filter::detail::RowPattern;
  using meridian::filter::detail::predict_covariance;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g;
  const DovParameters p;
  const Matrix<n, n> q = meridian::filter::discretise(dov_model(p), 0.01).q;
  for (int trial = 0; trial < 50; ++trial) {
    Matrix<n, n> a;
    for (Index i = 0; i < a.size(); ++i) a.data()[i] = g(rng);
    const Matrix<n, n> P = (a * a.transpose()).eval();  // exactly symmetric
    Matrix<n, n> phi = meridian::filter::discretise(dov_model(p), 0.01 * (1 + trial)).phi;
    if (trial % 2 == 1) phi(DovState::x_e, DovState::delta_eta) = 0.0;  // a zero inside
    ASSERT_TRUE(kDovKernel.fits(phi));
    const RowPattern<n, n> pattern(phi);
    Matrix<n, n> want, want_pphit, got, got_pphit;
    predict_covariance(phi, P, q, pattern, want, want_pphit);
    kDovKernel.predict(phi, P, q, got, &got_pphit);
    EXPECT_TRUE(got == want) << trial;  // == : equal up to the sign of a zero
    EXPECT_TRUE(got_pphit == want_pphit) << trial;
    kDovKernel.predict(phi, P, q, got, nullptr);
    EXPECT_TRUE(got == want) << trial;
  }
  Matrix<n, n> outside = Matrix<n, n>::Identity();
  EXPECT_TRUE(kDovKernel.fits(outside));
  outside(DovState::eps_u, DovState::phi_e) = 1e-9;
  EXPECT_FALSE(kDovKernel.fits(outside));
  outside(DovState::eps_u, DovState::phi_e) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(kDovKernel.fits(outside));
}

TEST(StructuredTransition, FilterAndSmootherGiveTheGenericResultsBitForBit) {
  const ScratchDir dir;
  const auto line = dov_line(2000, 31);
  constexpr int n = DovState::size;
  const std::size_t compact_bytes = SmootherStorage<n>::compact_record_doubles(n) * sizeof(double);
  constexpr std::size_t never = std::numeric_limits<std::size_t>::max();
  SmootherStorage<n> generic(n, {never, dir.path, 1 << 20});
  SmootherStorage<n> structured(n, {never, dir.path, 1 << 20});
  SmootherStorage<n> spilled(n, {300 * compact_bytes, dir.path, 64 << 10});
  forward(line, generic, true);
  forward(line, structured, true, &kDovKernel);
  forward(line, spilled, true, &kDovKernel);
  const auto a = rts_smooth(generic);
  EXPECT_TRUE(bit_identical(a, rts_smooth(structured)));
  EXPECT_TRUE(bit_identical(a, rts_smooth(spilled)));
  // The filtered estimates and the P⁻ the reader recomputes, epoch by epoch.
  auto rg = generic.read_reverse();
  auto rs = spilled.read_reverse();
  EpochRecord<n> x, y;
  while (rg.next(x)) {
    ASSERT_TRUE(rs.next(y));
    EXPECT_TRUE(x.predicted.P == y.predicted.P) << rg.index();
    EXPECT_TRUE(x.filtered.P == y.filtered.P) << rg.index();
    EXPECT_TRUE(x.filtered.x == y.filtered.x) << rg.index();
  }
  // A Φ outside the structure takes the generic path: still the same numbers.
  KalmanFilter<n> k1(line.initial), k2(line.initial);
  k2.set_transition_kernel(&kDovKernel);
  Matrix<n, n> odd = line.steps[1].phi;
  odd(DovState::eps_u, DovState::x_e) = 1e-6;
  for (KalmanFilter<n>* k : {&k1, &k2}) {
    k->predict(odd, line.steps[1].q);
    k->update(line.z[1], line.H, line.R);
    k->predict(line.steps[1]);
  }
  EXPECT_TRUE(k1.estimate().P == k2.estimate().P);
  EXPECT_TRUE(dir.empty());
}

TEST(SmootherStorage, CompactRecordsNeedEveryEpochOfOneLayout) {
  const auto line = dov_line(4, 29);
  constexpr int n = DovState::size;
  KalmanFilter<n> kf(line.initial);
  {  // an epoch skipped
    SmootherStorage<n> storage;
    storage.append(kf);
    kf.predict(line.steps[1]);
    kf.predict(line.steps[2]);
    const auto c = catch_error<InputError>([&] { storage.append(kf); });
    EXPECT_TRUE(c.thrown);
    EXPECT_EQ(c.field, "epoch 1");
    EXPECT_THAT(c.what, ::testing::HasSubstr("the filter is at epoch 2"));
  }
  KalmanFilter<n> kf0(line.initial);
  {  // full, then compact
    SmootherStorage<n> storage;
    storage.append(kf0.predicted(), kf0.transition(), kf0.estimate());
    KalmanFilter<n> kf1 = kf0;
    kf1.predict(line.steps[1]);
    const auto c = catch_error<InputError>([&] { storage.append(kf1); });
    EXPECT_TRUE(c.thrown);
    EXPECT_THAT(c.what, ::testing::HasSubstr("holds full records"));
  }
  {  // compact, then full
    SmootherStorage<n> storage;
    storage.append(kf0);
    const auto c = catch_error<InputError>(
        [&] { storage.append(kf0.predicted(), kf0.transition(), kf0.estimate()); });
    EXPECT_TRUE(c.thrown);
    EXPECT_EQ(c.field, "epoch 1");
    EXPECT_THAT(c.what, ::testing::HasSubstr("holds compact records"));
  }
}

TEST(SmootherStorage, CompactSpillFileHasTheDocumentedFormat) {
  const ScratchDir dir;
  const auto line = dov_line(10, 30);
  constexpr int n = DovState::size;
  std::vector<Estimate<n>> predicted;
  std::vector<Estimate<n>> filtered;
  SmootherStorage<n> storage(n, StorageOptions{0, dir.path, 1 << 20, false});
  KalmanFilter<n> kf(line.initial);
  for (Index k = 0; k < line.size(); ++k) {
    if (k > 0) kf.predict(line.steps[static_cast<std::size_t>(k)]);
    kf.update(line.z[static_cast<std::size_t>(k)], line.H, line.R);
    storage.append(kf);
    predicted.push_back(kf.predicted());
    filtered.push_back(kf.estimate());
  }
  storage.read_reverse();  // flushes and writes the counts
  std::ifstream in(storage.spill_path(), std::ios::binary);
  char magic[8];
  std::uint32_t version, state_size, record_bytes;
  std::uint64_t count;
  in.read(magic, 8);
  in.read(reinterpret_cast<char*>(&version), 4);
  in.read(reinterpret_cast<char*>(&state_size), 4);
  in.read(reinterpret_cast<char*>(&count), 8);
  in.read(reinterpret_cast<char*>(&record_bytes), 4);
  EXPECT_EQ(std::string(magic, 8), "MRDN-RTS");
  EXPECT_EQ(version, 2u);
  EXPECT_EQ(state_size, 8u);
  EXPECT_EQ(count, 10u);
  EXPECT_EQ(record_bytes, 8u * (1 + 2 * 8 + 36));
  // Record 3: index of (Φ_3, Q_3), x̂⁻_3, x̂_3, P_3 upper triangle column by column.
  std::vector<double> rec(record_bytes / 8);
  in.seekg(32 + 3 * record_bytes);
  in.read(reinterpret_cast<char*>(rec.data()), record_bytes);
  EXPECT_EQ(rec[0], 1.0);
  EXPECT_EQ(rec[1 + 2], predicted[3].x(2));
  EXPECT_EQ(rec[9 + 2], filtered[3].x(2));
  EXPECT_EQ(rec[17 + 0], filtered[3].P(0, 0));
  EXPECT_EQ(rec[17 + 3], filtered[3].P(0, 2));
  // Transition 1: Φ then Q_d as the filter used it (½(Q + Qᵀ)), column-major.
  std::ifstream tin(storage.transition_path(), std::ios::binary);
  tin.seekg(8);
  tin.read(reinterpret_cast<char*>(&version), 4);
  tin.seekg(16);
  tin.read(reinterpret_cast<char*>(&count), 8);
  tin.read(reinterpret_cast<char*>(&record_bytes), 4);
  EXPECT_EQ(version, 2u);
  EXPECT_EQ(count, 2u);
  EXPECT_EQ(record_bytes, 8u * 128u);
  std::vector<double> t(128);
  tin.seekg(32 + 1024);
  tin.read(reinterpret_cast<char*>(t.data()), 1024);
  const auto& step = line.steps[3];
  EXPECT_EQ(t[1], step.phi(1, 0));
  EXPECT_EQ(t[64 + 9], 0.5 * (step.q(1, 1) + step.q(1, 1)));
  EXPECT_EQ(t[64 + 8], 0.5 * (step.q(0, 1) + step.q(1, 0)));
}

TEST(SmootherStorage, SpillFileHasTheDocumentedFormatAndIsRemoved) {
  const ScratchDir dir;
  const auto line = dov_line(10, 25);
  constexpr int n = DovState::size;
  fs::path path;
  fs::path phi_path;
  std::vector<Estimate<n>> predicted;
  std::vector<Estimate<n>> filtered;
  {
    StorageOptions options{0, dir.path, 1 << 20, false};
    SmootherStorage<n> storage(n, options);
    KalmanFilter<n> kf(line.initial);
    for (Index k = 0; k < line.size(); ++k) {
      if (k > 0) kf.predict(line.steps[static_cast<std::size_t>(k)]);
      kf.update(line.z[static_cast<std::size_t>(k)], line.H, line.R);
      storage.append(kf.predicted(), kf.transition(), kf.estimate());
      predicted.push_back(kf.predicted());
      filtered.push_back(kf.estimate());
    }
    path = storage.spill_path();
    ASSERT_FALSE(path.empty());
    EXPECT_EQ(path.parent_path(), dir.path);
    EXPECT_EQ(fs::status(path).permissions() & fs::perms::all,
              fs::perms::owner_read | fs::perms::owner_write);
    storage.read_reverse();  // flushes and writes the count

    std::ifstream in(path, std::ios::binary);
    char magic[8];
    std::uint32_t version, state_size, record_bytes, bom;
    std::uint64_t count;
    in.read(magic, 8);
    in.read(reinterpret_cast<char*>(&version), 4);
    in.read(reinterpret_cast<char*>(&state_size), 4);
    in.read(reinterpret_cast<char*>(&count), 8);
    in.read(reinterpret_cast<char*>(&record_bytes), 4);
    in.read(reinterpret_cast<char*>(&bom), 4);
    EXPECT_EQ(std::string(magic, 8), "MRDN-RTS");
    EXPECT_EQ(version, 1u);
    EXPECT_EQ(state_size, 8u);
    EXPECT_EQ(count, 10u);
    EXPECT_EQ(record_bytes, 8u * (1 + 2 * 8 + 8 * 9));
    EXPECT_EQ(bom, 0x01020304u);
    EXPECT_EQ(fs::file_size(path), 32u + 10u * record_bytes);
    // Record 3: index of Φ_3, x̂⁻_3, P⁻_3 upper triangle column by column, x̂_3, P_3.
    std::vector<double> rec(record_bytes / 8);
    in.seekg(32 + 3 * record_bytes);
    in.read(reinterpret_cast<char*>(rec.data()), record_bytes);
    EXPECT_EQ(rec[0], 1.0);  // transition 0 is the identity of epoch 0, 1 the constant Φ
    EXPECT_EQ(rec[1 + 2], predicted[3].x(2));
    EXPECT_EQ(rec[9 + 0], predicted[3].P(0, 0));
    EXPECT_EQ(rec[9 + 1], predicted[3].P(0, 1));
    EXPECT_EQ(rec[9 + 2], predicted[3].P(1, 1));
    EXPECT_EQ(rec[9 + 3], predicted[3].P(0, 2));
    EXPECT_EQ(rec[45 + 2], filtered[3].x(2));
    EXPECT_EQ(rec[53 + 3], filtered[3].P(0, 2));

    // The transitions: Φ column-major, the identity then the line's constant Φ.
    phi_path = storage.transition_path();
    ASSERT_FALSE(phi_path.empty());
    std::ifstream tin(phi_path, std::ios::binary);
    tin.read(magic, 8);
    EXPECT_EQ(std::string(magic, 8), "MRDN-PHI");
    tin.seekg(16);
    tin.read(reinterpret_cast<char*>(&count), 8);
    tin.read(reinterpret_cast<char*>(&record_bytes), 4);
    EXPECT_EQ(count, 2u);
    EXPECT_EQ(record_bytes, 8u * 64u);
    std::vector<double> phi(64);
    tin.seekg(32);
    tin.read(reinterpret_cast<char*>(phi.data()), 512);
    EXPECT_EQ(phi[0], 1.0);
    EXPECT_EQ(phi[1], 0.0);
    tin.read(reinterpret_cast<char*>(phi.data()), 512);
    const auto& step = line.steps[3];
    EXPECT_EQ(phi[0], step.phi(0, 0));
    EXPECT_EQ(phi[1], step.phi(1, 0));
    EXPECT_EQ(phi[8], step.phi(0, 1));
  }
  EXPECT_FALSE(fs::exists(path));  // removed by the destructor
  EXPECT_FALSE(fs::exists(phi_path));

  // Removed when an exception unwinds the stack.
  try {
    SmootherStorage<n> storage(n, StorageOptions{0, dir.path, 1 << 20, false});
    forward(line, storage);
    path = storage.spill_path();
    ASSERT_TRUE(fs::exists(path));
    throw std::runtime_error("simulated failure of the workflow");
  } catch (const std::runtime_error&) {
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(dir.empty());
}

TEST(SmootherStorage, UnwritableDirectoryIsAnIoErrorNamingTheEpoch) {
  const auto line = dov_line(3, 26);
  constexpr int n = DovState::size;
  SmootherStorage<n> storage(n, StorageOptions{1300, "/nonexistent/meridian-test", 1 << 20});
  const auto c = catch_error<IoError>([&] { forward(line, storage); });
  EXPECT_TRUE(c.thrown);
  EXPECT_EQ(c.field, "epoch 1");  // the first record fits in memory, the second spills
  EXPECT_THAT(c.what, ::testing::HasSubstr("/nonexistent/meridian-test"));
}

TEST(Smoothers, RtsNamesTheEpochOfABadPredictedCovariance) {
  constexpr int n = 2;
  SmootherStorage<n> storage;
  const Estimate<n> good{Vector<n>::Zero(), Matrix<n, n>::Identity()};
  Estimate<n> bad = good;
  bad.P(1, 1) = -1.0;
  storage.append(good, Matrix<n, n>::Identity(), good);
  storage.append(good, Matrix<n, n>::Identity(), good);
  storage.append(bad, Matrix<n, n>::Identity(), good);
  storage.append(good, Matrix<n, n>::Identity(), good);
  const auto c = catch_error<NumericalError>([&] { rts_smooth(storage); });
  EXPECT_TRUE(c.thrown);
  EXPECT_EQ(c.field, "epoch 2");
  EXPECT_THAT(c.what, ::testing::HasSubstr("predicted covariance"));
}

TEST(TwoFilter, CombineIndependentIsRtklibsFormula) {
  std::mt19937_64 rng(27);
  constexpr int n = 4;
  const auto random_spd = [&] {
    Matrix<n, n> a;
    std::normal_distribution<double> nd;
    for (Index i = 0; i < a.size(); ++i) a.data()[i] = nd(rng);
    return (a * a.transpose() + 0.1 * Matrix<n, n>::Identity()).eval();
  };
  const Estimate<n> a{Vector<n>(1.0, 2.0, -1.0, 0.5), random_spd()};
  const Estimate<n> b{Vector<n>(1.5, 1.0, -2.0, 0.0), random_spd()};
  const auto s = meridian::filter::combine_independent(a, b, 0);
  // xs = Qs·(Qa⁻¹·xa + Qb⁻¹·xb), Qs = (Qa⁻¹ + Qb⁻¹)⁻¹ with explicit inverses.
  const Matrix<n, n> qs = (a.P.inverse() + b.P.inverse()).inverse();
  const Vector<n> xs = qs * (a.P.inverse() * a.x + b.P.inverse() * b.x);
  EXPECT_LT(state_difference(s.x, xs, qs), 1e-12);
  EXPECT_LT(covariance_difference(s.P, qs), 1e-12);
}

}  // namespace
