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
/// Two spill files, version 1 (all numbers in host byte order, doubles IEEE-754 binary64;
/// private to the process and never read elsewhere), each with the header
///
///   offset  size  field
///        0     8  magic: "MRDN-RTS" (epoch records) or "MRDN-PHI" (transitions)
///        8     4  uint32 format version = 1
///       12     4  uint32 state size n
///       16     8  uint64 record count (0 until the first read; then exact)
///       24     4  uint32 record size in bytes
///       28     4  uint32 byte-order mark 0x01020304
///       32        the records, fixed size, in order:
///   epoch record k (8·(1 + 2n + n(n+1)) bytes): the index j of Φ_k in the transitions file as
///                 a double (an exact integer), x̂⁻_k (n), P⁻_k (upper triangle, column by
///                 column: P(0,0), P(0,1), P(1,1), P(0,2), …: n(n+1)/2), x̂_k (n), P_k (upper
///                 triangle, n(n+1)/2);
///   transition j (8·n² bytes): Φ, column-major; Φ_k is transition j of epoch k, the identity
///                 at k = 0; j never decreases with k.
///
/// For n = 8 an epoch record is 712 bytes: 10⁷ epochs take 7.1 GB of disk (plus 512 bytes per
/// change of Φ) and O(buffers) memory. Each store keeps its records in memory up to
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
        store_(kSpillMagic, static_cast<std::uint32_t>(n_), record_doubles(n_), options),
        transitions_(kTransitionMagic, static_cast<std::uint32_t>(n_),
                     static_cast<std::size_t>(n_ * n_), std::move(options)),
        last_phi_(Matrix<N, N>::Zero(n_, n_)) {}

  /// Append epoch k = size(): the predicted estimate, the transition Φ_k that led to it and
  /// the filtered estimate (KalmanFilter::predicted(), transition(), estimate()). Throws
  /// InputError when a size does not match, IoError when a spill file cannot be written.
  void append(const Estimate<N>& predicted, const Matrix<N, N>& phi, const Estimate<N>& filtered) {
    const auto epoch = static_cast<Eigen::Index>(store_.size());
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

  /// Number of epochs stored.
  Eigen::Index size() const { return static_cast<Eigen::Index>(store_.size()); }
  /// Number of transitions stored: one per change of Φ from one epoch to the next (2 for a
  /// line with a constant Φ: the identity of epoch 0 and Φ).
  Eigen::Index transitions() const { return static_cast<Eigen::Index>(transitions_.size()); }
  /// Number of states.
  Eigen::Index state_size() const { return n_; }
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
      const double* p = reader_.next();
      if (p == nullptr) return false;
      const Eigen::Index n = n_;
      const auto j = static_cast<std::uint64_t>(*p++);
      while (!have_phi_ || phi_reader_.index() != j) {
        const double* t = phi_reader_.next();
        if (t == nullptr || phi_reader_.index() < j) [[unlikely]]
          throw IoError("the smoother's epoch record refers to a transition that is not stored",
                        ErrorContext{{}, {}, detail::epoch_field(index())});
        if (phi_reader_.index() == j) {
          phi_.resize(n, n);
          for (Eigen::Index i = 0; i < n * n; ++i) phi_.data()[i] = t[i];
        }
        have_phi_ = true;
      }
      p = unpack(p, predicted, n);
      unpack(p, filtered, n);
      return true;
    }
    /// Epoch of the record the last next() filled.
    Eigen::Index index() const { return static_cast<Eigen::Index>(reader_.index()); }
    /// Φ of that epoch (from epoch index() − 1 to index()).
    const Matrix<N, N>& transition() const { return phi_; }
    /// Index of transition() in the store of transitions: it changes only when Φ does.
    std::uint64_t transition_index() const { return phi_reader_.index(); }

   private:
    friend class SmootherStorage;
    ReverseReader(detail::RecordStore::ReverseReader reader,
                  detail::RecordStore::ReverseReader phi_reader, Eigen::Index n)
        : reader_(std::move(reader)), phi_reader_(std::move(phi_reader)), n_(n) {}
    detail::RecordStore::ReverseReader reader_;
    detail::RecordStore::ReverseReader phi_reader_;
    Matrix<N, N> phi_;
    bool have_phi_ = false;
    Eigen::Index n_;
  };
  /// Start reading (may be called again for another pass). Throws IoError when a spill file
  /// cannot be flushed or its header or size is not as written.
  ReverseReader read_reverse() {
    return ReverseReader(store_.read_reverse(), transitions_.read_reverse(), n_);
  }

  /// Doubles per epoch record: 1 + 2n + n(n + 1).
  static std::size_t record_doubles(Eigen::Index n) {
    return static_cast<std::size_t>(1 + 2 * n + n * (n + 1));
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
  detail::RecordStore store_;
  detail::RecordStore transitions_;
  Matrix<N, N> last_phi_;
};

}  // namespace meridian::filter
