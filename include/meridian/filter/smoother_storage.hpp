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
/// Spill file format, version 1 (all numbers in host byte order, doubles IEEE-754 binary64;
/// the file is private to the process and never read elsewhere):
///
///   offset  size  field
///        0     8  magic "MRDN-RTS" (ASCII, no terminator)
///        8     4  uint32 format version = 1
///       12     4  uint32 state size n
///       16     8  uint64 record count K (0 until the first read; then exact)
///       24     4  uint32 record size in bytes = 8·(2n² + 3n)
///       28     4  uint32 byte-order mark 0x01020304
///       32        K records of fixed size; record k (k = 0…K−1) holds, as doubles:
///                 Φ_k (n², column-major; Φ_0 = I), x̂⁻_k (n), P⁻_k (upper triangle, column by
///                 column: P(0,0), P(0,1), P(1,1), P(0,2), …: n(n+1)/2), x̂_k (n), P_k (upper
///                 triangle, n(n+1)/2).
///
/// For n = 8 a record is 1216 bytes: 10⁷ epochs take 12.2 GB of disk and O(buffer) memory.
/// The file is created with mkostemp (mode 0600, O_EXCL) in StorageOptions::spill_directory
/// (default std::filesystem::temp_directory_path()), unlinked at once unless
/// StorageOptions::anonymous is false, and closed (removed) by the destructor — also when an
/// exception unwinds the stack.

#include <cstdint>
#include <utility>

#include "meridian/filter/detail/checks.hpp"
#include "meridian/filter/detail/record_store.hpp"
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
        store_(static_cast<std::uint32_t>(n_), record_doubles(n_), std::move(options)) {}

  /// Append epoch k = size(): the predicted estimate, the transition Φ_k that led to it and
  /// the filtered estimate (KalmanFilter::predicted(), transition(), estimate()). Throws
  /// InputError when a size does not match, IoError when the spill file cannot be written.
  void append(const Estimate<N>& predicted, const Matrix<N, N>& phi,
              const Estimate<N>& filtered) {
    const auto epoch = static_cast<Eigen::Index>(store_.size());
    detail::check_shape(phi.rows(), phi.cols(), n_, n_, "transition Φ", epoch);
    detail::check_shape(predicted.P.rows(), predicted.x.rows(), n_, n_, "predicted estimate",
                        epoch);
    detail::check_shape(filtered.P.rows(), filtered.x.rows(), n_, n_, "filtered estimate",
                        epoch);
    double* p = store_.append();
    for (Eigen::Index j = 0; j < n_ * n_; ++j) *p++ = phi.data()[j];
    p = pack(predicted, p);
    pack(filtered, p);
  }

  /// Number of epochs stored.
  Eigen::Index size() const { return static_cast<Eigen::Index>(store_.size()); }
  /// Number of states.
  Eigen::Index state_size() const { return n_; }
  /// True once the records live in the spill file.
  bool spilled() const { return store_.spilled(); }
  /// Bytes of the spill file (0 in memory).
  std::uint64_t file_bytes() const { return store_.file_bytes(); }
  /// The spill file's path when it has a name (StorageOptions::anonymous = false).
  const std::filesystem::path& spill_path() const { return store_.path(); }

  /// Reads the epochs last first: next(record) fills `record` with epoch index() and returns
  /// true, false after epoch 0. Do not append while reading. Throws IoError on a read error.
  class ReverseReader {
   public:
    bool next(EpochRecord<N>& record) {
      const double* p = reader_.next();
      if (p == nullptr) return false;
      const Eigen::Index n = n_;
      record.phi.resize(n, n);
      for (Eigen::Index j = 0; j < n * n; ++j) record.phi.data()[j] = *p++;
      p = unpack(p, record.predicted, n);
      unpack(p, record.filtered, n);
      return true;
    }
    /// Epoch of the record the last next() filled.
    Eigen::Index index() const { return static_cast<Eigen::Index>(reader_.index()); }

   private:
    friend class SmootherStorage;
    ReverseReader(detail::RecordStore::ReverseReader reader, Eigen::Index n)
        : reader_(std::move(reader)), n_(n) {}
    detail::RecordStore::ReverseReader reader_;
    Eigen::Index n_;
  };
  /// Start reading (may be called again for another pass). Throws IoError when the spill file
  /// cannot be flushed or its header or size is not as written.
  ReverseReader read_reverse() { return ReverseReader(store_.read_reverse(), n_); }

  /// Doubles per record: 2n² + 3n.
  static std::size_t record_doubles(Eigen::Index n) {
    return static_cast<std::size_t>(2 * n * n + 3 * n);
  }

 private:
  static Eigen::Index checked_size(Eigen::Index n) {
    if (n < 1 || (N != Eigen::Dynamic && n != N))
      detail::throw_input(0, "state size of the smoother storage must be ≥ 1 and equal N");
    return n;
  }
  static double* pack(const Estimate<N>& e, double* p) {
    const Eigen::Index n = e.x.size();
    for (Eigen::Index i = 0; i < n; ++i) *p++ = e.x(i);
    for (Eigen::Index j = 0; j < n; ++j)
      for (Eigen::Index i = 0; i <= j; ++i) *p++ = e.P(i, j);
    return p;
  }
  static const double* unpack(const double* p, Estimate<N>& e, Eigen::Index n) {
    e.x.resize(n);
    e.P.resize(n, n);
    for (Eigen::Index i = 0; i < n; ++i) e.x(i) = *p++;
    for (Eigen::Index j = 0; j < n; ++j)
      for (Eigen::Index i = 0; i <= j; ++i) e.P(i, j) = e.P(j, i) = *p++;
    return p;
  }

  Eigen::Index n_;
  detail::RecordStore store_;
};

}  // namespace meridian::filter
