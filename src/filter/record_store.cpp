#include "meridian/filter/detail/record_store.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>
#include <system_error>
#include <utility>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/scratch_array.hpp"
#include "meridian/filter/detail/checks.hpp"

namespace meridian::filter::detail {
namespace {

// Header of the spill file: 32 bytes, host byte order (the file never leaves the process).
struct Header {
  char magic[8];
  std::uint32_t version;
  std::uint32_t state_size;
  std::uint64_t record_count;
  std::uint32_t record_bytes;
  std::uint32_t byte_order_mark;
};
static_assert(sizeof(Header) == kSpillHeaderBytes);

// In-memory chunks: 2 MB, the size of an x86-64 transparent huge page.
constexpr std::size_t kChunkBytes = std::size_t{2} << 20;

[[noreturn]] void throw_io(std::uint64_t epoch, const std::string& what, int error) {
  throw IoError(fmt::format("{}: {}", what, std::generic_category().message(error)),
                ErrorContext{{}, {}, epoch_field(static_cast<Eigen::Index>(epoch))});
}

// write/pwrite the whole buffer, retrying partial writes and EINTR.
void write_all(int fd, const void* data, std::size_t bytes, off_t offset, std::uint64_t epoch) {
  const char* p = static_cast<const char*>(data);
  while (bytes > 0) {
    const ssize_t n = ::pwrite(fd, p, bytes, offset);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw_io(epoch, "cannot write the smoother's spill file", errno);
    }
    p += n;
    bytes -= static_cast<std::size_t>(n);
    offset += n;
  }
}

void read_all(int fd, void* data, std::size_t bytes, off_t offset, std::uint64_t epoch) {
  char* p = static_cast<char*>(data);
  while (bytes > 0) {
    const ssize_t n = ::pread(fd, p, bytes, offset);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw_io(epoch, "cannot read the smoother's spill file", errno);
    }
    if (n == 0)
      throw IoError("the smoother's spill file is shorter than written",
                    ErrorContext{{}, {}, epoch_field(static_cast<Eigen::Index>(epoch))});
    p += n;
    bytes -= static_cast<std::size_t>(n);
    offset += n;
  }
}

}  // namespace

RecordStore::RecordStore(const char* magic, std::uint32_t state_size, std::size_t record_doubles,
                         StorageOptions options, std::uint32_t version)
    : magic_(magic),
      version_(version),
      state_size_(state_size),
      record_doubles_(record_doubles),
      options_(std::move(options)) {
  const std::size_t record_bytes = record_doubles_ * sizeof(double);
  buffer_records_ = std::max<std::size_t>(1, options_.buffer_bytes / record_bytes);
  chunk_records_ =
      std::max<std::size_t>(1, std::min(kChunkBytes, options_.memory_limit_bytes) / record_bytes);
}

RecordStore::~RecordStore() { close(); }

RecordStore::RecordStore(RecordStore&& other) noexcept
    : magic_(other.magic_),
      version_(other.version_),
      state_size_(other.state_size_),
      record_doubles_(other.record_doubles_),
      options_(std::move(other.options_)),
      count_(other.count_),
      chunks_(std::move(other.chunks_)),
      chunk_records_(other.chunk_records_),
      chunk_fill_(other.chunk_fill_),
      buffer_(std::move(other.buffer_)),
      buffered_(other.buffered_),
      buffer_records_(other.buffer_records_),
      fd_(std::exchange(other.fd_, -1)),
      path_(std::move(other.path_)) {
  other.path_.clear();
  other.count_ = 0;
  other.chunks_.clear();
  other.chunk_fill_ = 0;
  other.buffered_ = 0;
}

RecordStore& RecordStore::operator=(RecordStore&& other) noexcept {
  if (this != &other) {
    close();
    magic_ = other.magic_;
    version_ = other.version_;
    state_size_ = other.state_size_;
    record_doubles_ = other.record_doubles_;
    options_ = std::move(other.options_);
    count_ = std::exchange(other.count_, 0);
    chunks_ = std::move(other.chunks_);
    other.chunks_.clear();
    chunk_records_ = other.chunk_records_;
    chunk_fill_ = std::exchange(other.chunk_fill_, 0);
    buffer_ = std::move(other.buffer_);
    buffered_ = std::exchange(other.buffered_, 0);
    buffer_records_ = other.buffer_records_;
    fd_ = std::exchange(other.fd_, -1);
    path_ = std::move(other.path_);
    other.path_.clear();
  }
  return *this;
}

void RecordStore::close() noexcept {
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
  }
  if (!path_.empty()) {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
    path_.clear();
  }
}

std::uint64_t RecordStore::file_bytes() const {
  if (fd_ < 0) return 0;
  return kSpillHeaderBytes + count_ * record_doubles_ * sizeof(double);
}

void RecordStore::add_chunk() {
  std::size_t bytes = chunk_records_ * record_doubles_ * sizeof(double);
  // With a memory limit of at least 2 MB the chunks after the first are whole multiples of
  // 2 MB, aligned to 2 MB and offered as transparent huge pages: one page fault (and one kernel
  // zero-fill) per chunk. The first is not, so a store that stays small (the transitions of a
  // constant model: two records) keeps ordinary 4 kB pages instead of a resident 2 MB. Nothing
  // is zero-filled here: every record is written in full by the caller before it is read.
  const bool huge = options_.memory_limit_bytes >= kChunkBytes && !chunks_.empty();
  if (huge) bytes = (bytes + kChunkBytes - 1) / kChunkBytes * kChunkBytes;
  void* p = huge ? std::aligned_alloc(kChunkBytes, bytes) : std::malloc(bytes);
  if (p == nullptr) throw std::bad_alloc();
  if (huge) advise_huge_pages(p, bytes);  // advice only: failure is harmless
  chunks_.emplace_back(static_cast<double*>(p));
  chunk_fill_ = 0;
}

double* RecordStore::append(std::uint64_t epoch) {
  if (fd_ < 0) {
    if ((count_ + 1) * record_doubles_ * sizeof(double) > options_.memory_limit_bytes) {
      spill(epoch);
    } else {
      if (chunks_.empty() || chunk_fill_ == chunk_records_) add_chunk();
      double* slot = chunks_.back().get() + chunk_fill_ * record_doubles_;
      ++chunk_fill_;
      ++count_;
      return slot;
    }
  }
  if (buffered_ == buffer_records_) flush(epoch);
  double* slot = buffer_.get() + buffered_ * record_doubles_;
  ++buffered_;
  ++count_;
  return slot;
}

void RecordStore::spill(std::uint64_t epoch) {
  std::filesystem::path dir = options_.spill_directory;
  try {
    if (dir.empty()) dir = std::filesystem::temp_directory_path();
  } catch (const std::filesystem::filesystem_error& e) {
    throw_io(epoch, "no temporary directory for the smoother's spill file", e.code().value());
  }
  std::string name = (dir / "meridian-smoother-XXXXXX").string();
  // mkostemp: a new file (O_EXCL) with mode 0600 and a name nobody else can have chosen.
  const int fd = ::mkostemp(name.data(), O_CLOEXEC);
  if (fd < 0)
    throw_io(epoch, fmt::format("cannot create the smoother's spill file in {}", dir.string()),
             errno);
  fd_ = fd;
  if (options_.anonymous)
    ::unlink(name.c_str());
  else
    path_ = name;

  Header h{};
  std::memcpy(h.magic, magic_, sizeof h.magic);
  h.version = version_;
  h.state_size = state_size_;
  h.record_count = 0;  // written by flush()
  h.record_bytes = static_cast<std::uint32_t>(record_doubles_ * sizeof(double));
  h.byte_order_mark = kSpillByteOrderMark;
  write_all(fd_, &h, sizeof h, 0, epoch);
  // The records kept in memory so far go first, chunk by chunk; then the chunks are freed and
  // the write buffer takes their place.
  const std::size_t record_bytes = record_doubles_ * sizeof(double);
  off_t offset = static_cast<off_t>(kSpillHeaderBytes);
  for (std::size_t i = 0; i < chunks_.size(); ++i) {
    const std::size_t records = i + 1 < chunks_.size() ? chunk_records_ : chunk_fill_;
    write_all(fd_, chunks_[i].get(), records * record_bytes, offset, epoch);
    offset += static_cast<off_t>(records * record_bytes);
  }
  std::vector<Chunk>().swap(chunks_);
  chunk_fill_ = 0;
  buffer_.reset(new double[buffer_records_ * record_doubles_]);  // not zero-filled
  buffered_ = 0;
}

void RecordStore::flush(std::uint64_t epoch) {
  if (fd_ < 0 || buffered_ == 0) return;
  const std::uint64_t first = count_ - buffered_;
  const std::size_t record_bytes = record_doubles_ * sizeof(double);
  write_all(fd_, buffer_.get(), buffered_ * record_bytes,
            static_cast<off_t>(kSpillHeaderBytes + first * record_bytes), epoch);
  buffered_ = 0;
}

RecordStore::ReverseReader RecordStore::read_reverse() {
  if (fd_ >= 0) {
    flush(count_);
    write_all(fd_, &count_, sizeof count_, offsetof(Header, record_count), count_);
    Header h{};
    read_all(fd_, &h, sizeof h, 0, count_);
    struct stat st {};
    if (::fstat(fd_, &st) != 0) throw_io(count_, "cannot inspect the smoother's spill file", errno);
    const std::size_t record_bytes = record_doubles_ * sizeof(double);
    if (std::memcmp(h.magic, magic_, sizeof h.magic) != 0 || h.version != version_ ||
        h.state_size != state_size_ || h.record_count != count_ || h.record_bytes != record_bytes ||
        h.byte_order_mark != kSpillByteOrderMark ||
        static_cast<std::uint64_t>(st.st_size) != kSpillHeaderBytes + count_ * record_bytes)
      throw IoError(
          fmt::format("the smoother's spill file is not as written ({} bytes for {} "
                      "records of {} bytes)",
                      st.st_size, count_, record_bytes));
  }
  return ReverseReader(*this);
}

RecordStore::ReverseReader::ReverseReader(const RecordStore& store)
    : store_(&store), first_(store.count_), remaining_(store.count_) {
  if (store.fd_ < 0 && !store.chunks_.empty()) {
    chunk_ = store.chunks_.size() - 1;
    slot_ = store.chunk_fill_;
  }
}

const double* RecordStore::ReverseReader::next() {
  if (remaining_ == 0) return nullptr;
  index_ = --remaining_;
  const std::size_t rd = store_->record_doubles_;
  if (store_->fd_ < 0) {
    if (slot_ == 0) {  // the last record of the chunk before
      --chunk_;
      slot_ = store_->chunk_records_;
    }
    --slot_;
    return store_->chunks_[chunk_].get() + slot_ * rd;
  }
  if (index_ < first_) {
    // Load the block of records that ends with index_.
    const std::uint64_t n = std::min<std::uint64_t>(store_->buffer_records_, index_ + 1);
    first_ = index_ + 1 - n;
    block_.resize(store_->buffer_records_ * rd);  // once per pass
    read_all(store_->fd_, block_.data(), n * rd * sizeof(double),
             static_cast<off_t>(kSpillHeaderBytes + first_ * rd * sizeof(double)), index_);
  }
  return block_.data() + (index_ - first_) * rd;
}

}  // namespace meridian::filter::detail
