#pragma once
/// \file smoother_storage.hpp
/// What the forward pass keeps for a smoother: per epoch the predicted estimate, the
/// transition that led to it and the filtered estimate — in memory for short lines and in a
/// temporary binary file for long ones, so memory stays flat for 10⁷ epochs. Read back last
/// epoch first by the smoothers (rts_smoother.hpp, two_filter_smoother.hpp).
///
/// Records are packed identically in memory and in the file (one packing routine), so the
/// two paths give bit-identical smoother results.
///
/// Compact: covariances are stored as upper triangles, and Φ only when it changes — a model
/// discretised once for the whole line stores one Φ, not one per epoch. Each epoch record
/// holds the index of its Φ in a second store of transitions (one Φ per change).
///
/// Two record layouts, chosen by the first append:
///   * full (append(predicted, Φ, filtered), spill format version 1): every record holds P⁻_k,
///     which may be anything the caller computed;
///   * compact (append(const KalmanFilter&), version 2): P⁻_k is not stored but recomputed in the
///     backward pass as Φ_k·P_{k−1}·Φ_kᵀ + Q_k by KalmanFilter::predicted_covariance (or the
///     filter's structured kernel, kalman_filter.hpp: TransitionKernel) — the
///     operations of the forward predict, so the smoothers' results are bit-identical to the
///     full layout's — from the filtered P_{k−1} of the record before and the Q_d kept beside
///     Φ. 40 % less to write and read back for n = 8 (424 bytes a record instead of 712).
///
/// Two spill files per layout (all numbers in host byte order, doubles IEEE-754 binary64;
/// private to the process and never read elsewhere), each with the header
///
///   offset  size  field
///        0     8  magic: "MRDN-RTS" (epoch records) or "MRDN-PHI" (transitions)
///        8     4  uint32 format version: 1 full, 2 compact
///       12     4  uint32 state size n
///       16     8  uint64 record count (0 until the first read; then exact)
///       24     4  uint32 record size in bytes
///       28     4  uint32 byte-order mark 0x01020304
///       32        the records, fixed size, in order:
///   epoch record k, full (8·(1 + 2n + n(n+1)) bytes): the index j of Φ_k in the transitions
///                 file as a double (an exact integer), x̂⁻_k (n), P⁻_k (upper triangle, column by
///                 column: P(0,0), P(0,1), P(1,1), P(0,2), …: n(n+1)/2), x̂_k (n), P_k (upper
///                 triangle, n(n+1)/2);
///   epoch record k, compact (8·(1 + 2n + n(n+1)/2) bytes): j, x̂⁻_k (n), x̂_k (n), P_k (upper
///                 triangle); P⁻_0 (the initial covariance) is kept in memory;
///   transition j, full (8·n² bytes): Φ, column-major; compact (16·n² bytes): Φ, then Q_d as
///                 KalmanFilter::process_noise() gave it, both column-major. Φ_k is transition
///                 j of epoch k (the identity, and Q_d = 0, at k = 0); j never decreases with k;
///                 a new transition is stored when Φ (or, compact, Q_d) changes bit for bit.
///
/// For n = 8 an epoch record is 712 bytes (full) or 424 bytes (compact): 10⁷ epochs take 7.1 or
/// 4.2 GB of disk (plus 512 or 1024 bytes per change of Φ) and O(buffers) memory. Each store
/// keeps its records in memory up to
/// StorageOptions::memory_limit_bytes, then spills; a file is created with mkostemp (mode 0600,
/// O_EXCL) in StorageOptions::spill_directory (default std::filesystem::temp_directory_path()),
/// unlinked at once unless StorageOptions::anonymous is false, and closed (removed) by the
/// destructor — also when an exception unwinds the stack.

#include <cstdint>
#include <utility>

#include "meridian/core/error.hpp"
#include "meridian/filter/detail/checks.hpp"
#include "meridian/filter/detail/record_store.hpp"
#include "meridian/filter/detail/small_matrix.hpp"
#include "meridian/filter/estimate.hpp"
#include "meridian/filter/kalman_filter.hpp"

namespace meridian::filter {

/// What the smoothers need of forward epoch k.
template <int N>
struct EpochRecord {
  Matrix<N, N> phi;       ///< Φ_k from epoch k−1 to k (identity at k = 0)
  Estimate<N> predicted;  ///< x̂⁻_k, P⁻_k (the initial estimate at k = 0)
  Estimate<N> filtered;   ///< x̂_k, P_k after the updates of epoch k
};

/// Forward records of one line of N-state epochs (N fixed or Eigen::Dynamic). Move-only.
template <int N>
class SmootherStorage {
 public:
  /// Storage for states of `state_size` (must equal N when N is fixed; ≥ 1). Throws
  /// InputError otherwise.
  explicit SmootherStorage(Eigen::Index state_size = N, StorageOptions options = {})
      : n_(checked_size(state_size)),
        options_(std::move(options)),
        store_(kSpillMagic, static_cast<std::uint32_t>(n_), record_doubles(n_), options_),
        transitions_(kTransitionMagic, static_cast<std::uint32_t>(n_),
                     static_cast<std::size_t>(n_ * n_), options_),
        last_phi_(Matrix<N, N>::Zero(n_, n_)),
        last_q_(Matrix<N, N>::Zero(n_, n_)) {}

  /// Append epoch k = size() in the full layout: the predicted estimate, the transition Φ_k
  /// that led to it and the filtered estimate (KalmanFilter::predicted(), transition(),
  /// estimate()); P⁻ may be anything the caller computed. Throws InputError when a size does
  /// not match or the storage holds compact records, IoError when a spill file cannot be
  /// written.
  void append(const Estimate<N>& predicted, const Matrix<N, N>& phi, const Estimate<N>& filtered) {
    const auto epoch = static_cast<Eigen::Index>(store_.size());
    if (compact_) [[unlikely]]
      detail::throw_input(epoch,
                          "the smoother storage holds compact records (append(filter)): an "
                          "epoch cannot be added with its own predicted covariance");
    detail::check_shape(phi.rows(), phi.cols(), n_, n_, "transition Φ", epoch);
    detail::check_shape(predicted.P.rows(), predicted.x.rows(), n_, n_, "predicted estimate",
                        epoch);
    detail::check_shape(filtered.P.rows(), filtered.x.rows(), n_, n_, "filtered estimate", epoch);
    if (transitions_.size() == 0 || !detail::same_bits(phi, last_phi_)) {  // bit for bit
      double* t = transitions_.append(static_cast<std::uint64_t>(epoch));
      for (Eigen::Index j = 0; j < n_ * n_; ++j) t[j] = phi.data()[j];
      last_phi_ = phi;
    }
    double* p = store_.append(static_cast<std::uint64_t>(epoch));
    *p++ = static_cast<double>(transitions_.size() - 1);
    p = pack(predicted, p);
    pack(filtered, p);
  }

  /// Append epoch k = size() in the compact layout, from the filter after the updates of that
  /// epoch: x̂⁻, Φ, Q_d and the filtered estimate; the predicted covariance is recomputed when the
  /// line is read back (bit for bit). Every epoch must be appended, in order: the filter must
  /// be at epoch size(). Throws InputError when the state size or the filter's epoch does not
  /// match or the storage holds full records, IoError when a spill file cannot be written.
  void append(const KalmanFilter<N>& filter) {
    const auto epoch = static_cast<Eigen::Index>(store_.size());
    if (filter.size() != n_) [[unlikely]]
      detail::throw_input(epoch, "the filter's state size differs from the smoother storage's");
    if (filter.epoch() != epoch) [[unlikely]]
      detail::throw_input(epoch, "append(filter) stores every epoch in order, but the filter is "
                                 "at epoch " + std::to_string(filter.epoch()));
    if (epoch == 0) {
      if (!compact_) {  // the first record chooses the layout: re-create the empty stores
        store_ = detail::RecordStore(kSpillMagic, static_cast<std::uint32_t>(n_),
                                     compact_record_doubles(n_), options_, kSpillVersionCompact);
        transitions_ = detail::RecordStore(kTransitionMagic, static_cast<std::uint32_t>(n_),
                                           static_cast<std::size_t>(2 * n_ * n_), options_,
                                           kSpillVersionCompact);
        compact_ = true;
      }
      initial_p_ = filter.predicted().P;
      kernel_ = filter.transition_kernel();
    } else if (!compact_) [[unlikely]] {
      detail::throw_input(epoch,
                          "the smoother storage holds full records (append(predicted, Φ, "
                          "filtered)): append(filter) cannot continue the line");
    }
    const Matrix<N, N>& phi = filter.transition();
    const Matrix<N, N>& q = filter.process_noise();
    if (transitions_.size() == 0 || !detail::same_bits(phi, last_phi_) ||
        !detail::same_bits(q, last_q_)) {
      double* t = transitions_.append(static_cast<std::uint64_t>(epoch));
      for (Eigen::Index j = 0; j < n_ * n_; ++j) t[j] = phi.data()[j];
      for (Eigen::Index j = 0; j < n_ * n_; ++j) t[n_ * n_ + j] = q.data()[j];
      last_phi_ = phi;
      last_q_ = q;
    }
    double* p = store_.append(static_cast<std::uint64_t>(epoch));
    *p++ = static_cast<double>(transitions_.size() - 1);
    const Vector<N>& xp = filter.predicted().x;
    const Eigen::Index n = N == Eigen::Dynamic ? n_ : N;
    MERIDIAN_UNROLL
    for (Eigen::Index i = 0; i < n; ++i) *p++ = xp(i);
    pack(filter.estimate(), p);
  }

  /// Number of epochs stored.
  Eigen::Index size() const { return static_cast<Eigen::Index>(store_.size()); }
  /// Number of transitions stored: one per change of Φ from one epoch to the next (2 for a
  /// line with a constant Φ: the identity of epoch 0 and Φ).
  Eigen::Index transitions() const { return static_cast<Eigen::Index>(transitions_.size()); }
  /// Number of states.
  Eigen::Index state_size() const { return n_; }
  /// True when the records are in the compact layout (append(const KalmanFilter&)).
  bool compact() const { return compact_; }
  /// True once the epoch records live in the spill file (the transitions spill on their own,
  /// when they outgrow the memory limit).
  bool spilled() const { return store_.spilled(); }
  /// Bytes of the two spill files (0 while in memory).
  std::uint64_t file_bytes() const { return store_.file_bytes() + transitions_.file_bytes(); }
  /// The epoch records' spill file when it has a name (StorageOptions::anonymous = false).
  const std::filesystem::path& spill_path() const { return store_.path(); }
  /// The transitions' spill file when it has a name.
  const std::filesystem::path& transition_path() const { return transitions_.path(); }

  /// Reads the epochs last first: next(record) fills `record` with epoch index() and returns
  /// true, false after epoch 0. Do not append while reading. Throws IoError on a read error or
  /// an inconsistent transition index.
  class ReverseReader {
   public:
    bool next(EpochRecord<N>& record) {
      if (!next(record.predicted, record.filtered)) return false;
      record.phi = phi_;
      return true;
    }
    /// As next(record) without copying Φ: fills the predicted and filtered estimates of epoch
    /// index(); its Φ is transition() until the next call.
    bool next(Estimate<N>& predicted, Estimate<N>& filtered) {
      if (compact_) return next_compact(predicted, filtered);
      const double* p = reader_.next();
      if (p == nullptr) return false;
      index_ = static_cast<Eigen::Index>(reader_.index());
      load_transition(static_cast<std::uint64_t>(*p++));
      p = unpack(p, predicted, n_);
      unpack(p, filtered, n_);
      return true;
    }
    /// Epoch of the record the last next() filled.
    Eigen::Index index() const { return index_; }
    /// Φ of that epoch (from epoch index() − 1 to index()).
    const Matrix<N, N>& transition() const { return phi_; }
    /// Index of transition() in the store of transitions: it changes only when Φ (or, in the
    /// compact layout, Q_d) does.
    std::uint64_t transition_index() const { return phi_reader_.index(); }
    /// P_k·Φ_{k+1}ᵀ for the epoch k = index() the last next() filled, when the reader already
    /// computed it (compact records, fixed N: the intermediate of P⁻_{k+1}, bit for bit what
    /// the product gives); nullptr otherwise (full records, dynamic sizes, the last epoch).
    const Matrix<N, N>* filtered_times_next_transition() const {
      return have_pphit_[cur_pphit_] ? &pphit_[cur_pphit_] : nullptr;
    }

   private:
    friend class SmootherStorage;
    // A compact record as read: transition index, x̂⁻, filtered estimate.
    struct Slot {
      std::uint64_t transition = 0;
      Eigen::Index epoch = 0;
      Vector<N> predicted_x;
      Estimate<N> filtered;
    };
    ReverseReader(detail::RecordStore::ReverseReader reader,
                  detail::RecordStore::ReverseReader phi_reader, Eigen::Index n, bool compact,
                  const Matrix<N, N>& initial_p, const TransitionKernel<N>* kernel)
        : reader_(std::move(reader)),
          phi_reader_(std::move(phi_reader)),
          n_(n),
          compact_(compact),
          kernel_(kernel) {
      if (compact_) initial_p_ = initial_p;
    }
    // Advance the transitions to index j (they are read last first, j never increases).
    void load_transition(std::uint64_t j) {
      while (!have_phi_ || phi_reader_.index() != j) {
        const double* t = phi_reader_.next();
        if (t == nullptr || phi_reader_.index() < j) [[unlikely]]
          throw IoError("the smoother's epoch record refers to a transition that is not stored",
                        ErrorContext{{}, {}, detail::epoch_field(index_)});
        if (phi_reader_.index() == j) {
          phi_.resize(n_, n_);
          for (Eigen::Index i = 0; i < n_ * n_; ++i) phi_.data()[i] = t[i];
          if (compact_) {
            q_.resize(n_, n_);
            for (Eigen::Index i = 0; i < n_ * n_; ++i) q_.data()[i] = t[n_ * n_ + i];
            pattern_ = KalmanFilter<N>::pattern_of(phi_);
            fits_kernel_ = kernel_ != nullptr && kernel_->fits(phi_);
          }
        }
        have_phi_ = true;
      }
    }
    bool read_slot(Slot& slot) {
      const double* p = reader_.next();
      if (p == nullptr) return false;
      slot.epoch = static_cast<Eigen::Index>(reader_.index());
      slot.transition = static_cast<std::uint64_t>(*p++);
      const Eigen::Index n = N == Eigen::Dynamic ? n_ : N;
      slot.predicted_x.resize(n);
      MERIDIAN_UNROLL
      for (Eigen::Index i = 0; i < n; ++i) slot.predicted_x(i) = *p++;
      unpack(p, slot.filtered, n_);
      return true;
    }
    // Compact: epoch k's P⁻ needs the filtered P of epoch k − 1, so the reader keeps one record
    // ahead (slots_[cur_] is epoch k, slots_[1 − cur_] receives k − 1).
    bool next_compact(Estimate<N>& predicted, Estimate<N>& filtered) {
      if (!have_slot_) {
        if (!read_slot(slots_[cur_])) return false;
        have_slot_ = true;
      }
      Slot& now = slots_[cur_];
      index_ = now.epoch;
      // The product computed at the last call (P_k·Φ_{k+1}ᵀ) is this epoch's; the buffer of the
      // one before receives P_{k−1}·Φ_kᵀ below.
      cur_pphit_ = 1 - cur_pphit_;
      have_pphit_[1 - cur_pphit_] = false;
      load_transition(now.transition);
      filtered = now.filtered;
      predicted.x = now.predicted_x;
      if (index_ == 0) {
        predicted.P = initial_p_;
        have_slot_ = false;  // the next call reads nothing more and returns false
        return true;
      }
      Slot& before = slots_[1 - cur_];
      if (!read_slot(before)) [[unlikely]]
        throw IoError("the smoother's compact records end before epoch 0",
                      ErrorContext{{}, {}, detail::epoch_field(index_)});
      predicted.P.resize(n_, n_);
      if constexpr (N != Eigen::Dynamic) {
        if (fits_kernel_)  // the forward predict's kernel: the same P⁻ bit for bit
          kernel_->predict(phi_, before.filtered.P, q_, predicted.P, &pphit_[1 - cur_pphit_]);
        else
          KalmanFilter<N>::predicted_covariance(phi_, pattern_, before.filtered.P, q_, predicted.P,
                                                &pphit_[1 - cur_pphit_]);
        have_pphit_[1 - cur_pphit_] = true;
      } else {
        KalmanFilter<N>::predicted_covariance(phi_, pattern_, before.filtered.P, q_, predicted.P);
      }
      cur_ = 1 - cur_;
      return true;
    }

    detail::RecordStore::ReverseReader reader_;
    detail::RecordStore::ReverseReader phi_reader_;
    Matrix<N, N> phi_;
    bool have_phi_ = false;
    Eigen::Index n_;
    Eigen::Index index_ = 0;
    bool compact_;
    // Compact layout only.
    Matrix<N, N> q_;
    typename KalmanFilter<N>::TransitionPattern pattern_{};
    const TransitionKernel<N>* kernel_;
    bool fits_kernel_ = false;  // transition() fits kernel_
    Matrix<N, N> initial_p_;
    Slot slots_[2];
    int cur_ = 0;
    bool have_slot_ = false;
    Matrix<N, N> pphit_[2];  // P_k·Φ_{k+1}ᵀ: [cur_pphit_] for epoch index()
    bool have_pphit_[2] = {false, false};
    int cur_pphit_ = 0;
  };
  /// Start reading (may be called again for another pass). Throws IoError when a spill file
  /// cannot be flushed or its header or size is not as written.
  ReverseReader read_reverse() {
    return ReverseReader(store_.read_reverse(), transitions_.read_reverse(), n_, compact_,
                         initial_p_, kernel_);
  }

  /// Doubles per epoch record of the full layout: 1 + 2n + n(n + 1).
  static std::size_t record_doubles(Eigen::Index n) {
    return static_cast<std::size_t>(1 + 2 * n + n * (n + 1));
  }
  /// Doubles per epoch record of the compact layout: 1 + 2n + n(n + 1)/2.
  static std::size_t compact_record_doubles(Eigen::Index n) {
    return static_cast<std::size_t>(1 + 2 * n + n * (n + 1) / 2);
  }

 private:
  static Eigen::Index checked_size(Eigen::Index n) {
    if (n < 1 || (N != Eigen::Dynamic && n != N))
      detail::throw_input(0, "state size of the smoother storage must be ≥ 1 and equal N");
    return n;
  }
  // Fixed N: the loops have compile-time bounds and are unrolled.
  static double* pack(const Estimate<N>& e, double* p) {
    const Eigen::Index n = N == Eigen::Dynamic ? e.x.size() : N;
    MERIDIAN_UNROLL
    for (Eigen::Index i = 0; i < n; ++i) *p++ = e.x(i);
    MERIDIAN_UNROLL
    for (Eigen::Index j = 0; j < n; ++j) {
      MERIDIAN_UNROLL
      for (Eigen::Index i = 0; i <= j; ++i) *p++ = e.P(i, j);
    }
    return p;
  }
  static const double* unpack(const double* p, Estimate<N>& e, Eigen::Index n_runtime) {
    const Eigen::Index n = N == Eigen::Dynamic ? n_runtime : N;
    e.x.resize(n);
    e.P.resize(n, n);
    MERIDIAN_UNROLL
    for (Eigen::Index i = 0; i < n; ++i) e.x(i) = *p++;
    MERIDIAN_UNROLL
    for (Eigen::Index j = 0; j < n; ++j) {
      MERIDIAN_UNROLL
      for (Eigen::Index i = 0; i <= j; ++i) e.P(i, j) = e.P(j, i) = *p++;
    }
    return p;
  }

  Eigen::Index n_;
  StorageOptions options_;
  detail::RecordStore store_;
  detail::RecordStore transitions_;
  Matrix<N, N> last_phi_;
  Matrix<N, N> last_q_;     // compact: Q_d of the last stored transition
  Matrix<N, N> initial_p_;  // compact: P⁻_0
  const TransitionKernel<N>* kernel_ = nullptr;  // compact: the filter's structured kernel
  bool compact_ = false;
};

}  // namespace meridian::filter
