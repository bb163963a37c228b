#pragma once
/// \file record_store.hpp
/// Internal: fixed-length records of doubles, kept in memory up to a limit and spilled to an
/// anonymous temporary file beyond it, read back last record first. The typed interface and
/// the file format are in smoother_storage.hpp; this is the byte mover behind it
/// (src/filter/record_store.cpp).

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <vector>

namespace meridian::filter {

/// Where the smoother's forward records are kept (smoother_storage.hpp).
struct StorageOptions {
  /// Records stay in memory while they take at most this many bytes — per store: the epoch
  /// records and the transitions each have this limit; at the first record beyond it all of
  /// them move to the spill file and later ones follow there. 0: spill from the first record;
  /// SIZE_MAX: never spill. In memory the records live in chunks of 2 MB (or of the limit, if
  /// smaller) that are never copied, re-allocated or zero-filled while the line grows; a 2 MB
  /// chunk is offered to the kernel as one transparent huge page (madvise), so a long line in
  /// memory costs one page fault per 2 MB instead of one per 4 kB.
  std::size_t memory_limit_bytes = std::size_t{32} << 20;
  /// Directory of the spill file; empty: std::filesystem::temp_directory_path().
  std::filesystem::path spill_directory;
  /// Size of each of the two I/O buffers (write, read) of the spill path, rounded to whole
  /// records (at least one).
  std::size_t buffer_bytes = std::size_t{1} << 20;
  /// true: the spill file is unlinked as soon as it is created, so it disappears when the
  /// storage is destroyed, on an exception and even when the process is killed; false: it
  /// keeps its name (meridian-smoother-XXXXXX in spill_directory) until the storage is
  /// destroyed, for inspection.
  bool anonymous = true;
};

/// The spill files' header (smoother_storage.hpp documents the format): the magic of the
/// epoch records' file and of the transitions' file.
inline constexpr char kSpillMagic[8] = {'M', 'R', 'D', 'N', '-', 'R', 'T', 'S'};
inline constexpr char kTransitionMagic[8] = {'M', 'R', 'D', 'N', '-', 'P', 'H', 'I'};
inline constexpr std::uint32_t kSpillVersion = 1;         ///< full records (P⁻ stored)
inline constexpr std::uint32_t kSpillVersionCompact = 2;  ///< compact records (P⁻ recomputed)
inline constexpr std::size_t kSpillHeaderBytes = 32;
inline constexpr std::uint32_t kSpillByteOrderMark = 0x01020304u;

namespace detail {

class RecordStore {
 public:
  /// Records of `record_doubles` doubles for a state of `state_size` (written to the header,
  /// after the 8 characters of `magic`, which must outlive the store, and `version`).
  RecordStore(const char* magic, std::uint32_t state_size, std::size_t record_doubles,
              StorageOptions options, std::uint32_t version = kSpillVersion);
  ~RecordStore();
  RecordStore(const RecordStore&) = delete;
  RecordStore& operator=(const RecordStore&) = delete;
  RecordStore(RecordStore&& other) noexcept;
  RecordStore& operator=(RecordStore&& other) noexcept;

  /// Space for the next record (record_doubles() doubles), valid until the next call of any
  /// member. Throws IoError naming `epoch` (the line's epoch being stored) when the spill file
  /// cannot be created or written.
  double* append(std::uint64_t epoch);
  /// Number of records appended.
  std::uint64_t size() const { return count_; }
  std::size_t record_doubles() const { return record_doubles_; }
  /// True once the records live in the spill file.
  bool spilled() const { return fd_ >= 0; }
  /// Bytes of the spill file (header and records, including those still buffered); 0 in memory.
  std::uint64_t file_bytes() const;
  /// Path of the spill file when it has a name (StorageOptions::anonymous = false), else empty.
  const std::filesystem::path& path() const { return path_; }

  /// Reads the records last first. Appending while a reader is in use is not allowed.
  class ReverseReader {
   public:
    /// The next record (last first), nullptr after the first one. Throws IoError when the
    /// spill file cannot be read.
    const double* next();
    /// Index of the record the last next() returned.
    std::uint64_t index() const { return index_; }

   private:
    friend class RecordStore;
    explicit ReverseReader(const RecordStore& store);
    const RecordStore* store_;
    std::vector<double> block_;  // spill path: records [first_, first_ + block count)
    std::uint64_t first_ = 0;    // index of block_'s first record
    std::uint64_t remaining_;    // records not yet returned
    std::uint64_t index_ = 0;
    std::size_t chunk_ = 0;  // in memory: chunk of the next record to return …
    std::size_t slot_ = 0;   // … which is the one before slot_ in that chunk
  };
  /// Flushes the write buffer and the header's count, checks the header, and starts reading.
  /// Throws IoError when the file cannot be written or its header or size is not as written.
  ReverseReader read_reverse();

 private:
  struct Free {
    void operator()(double* p) const noexcept { std::free(p); }
  };
  using Chunk = std::unique_ptr<double, Free>;

  void add_chunk();
  void spill(std::uint64_t epoch);
  void flush(std::uint64_t epoch);
  void close() noexcept;

  const char* magic_;
  std::uint32_t version_;
  std::uint32_t state_size_;
  std::size_t record_doubles_;
  StorageOptions options_;
  std::uint64_t count_ = 0;
  std::vector<Chunk> chunks_;       // in memory: chunk i holds records [i·chunk_records_, …)
  std::size_t chunk_records_ = 1;   // records per chunk
  std::size_t chunk_fill_ = 0;      // records in the last chunk
  std::unique_ptr<double[]> buffer_;  // spill path: the write buffer (not zero-filled)
  std::size_t buffered_ = 0;          // spill path: records in buffer_ not yet written
  std::size_t buffer_records_ = 1;
  int fd_ = -1;
  std::filesystem::path path_;
};

}  // namespace detail
}  // namespace meridian::filter
