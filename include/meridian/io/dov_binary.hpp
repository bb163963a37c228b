#pragma once
/// \file dov_binary.hpp
/// The compact binary line format of the deflection-of-the-vertical workflow, for long lines
/// (docs/file-formats.md, "DOV binary line"): the same fields as the line CSV (dov_files.hpp),
/// as IEEE-754 binary64 numbers in SI units and radians — exactly the members of dov::Sample and
/// dov::Truth, so a line written and read back gives the same doubles, bit for bit.
///
/// Layout, version 1; every number little-endian (a big-endian host swaps on read and write):
///
///   offset  size  field
///        0     8  magic "MRDN-DOV" (ASCII)
///        8     4  uint32 format version = 1
///       12     4  uint32 flags: bit 0 = the model columns η_G, ξ_G are present, bit 1 = the
///                 truth columns are present; other bits 0
///       16     4  uint32 record size in bytes = 8 × (23 + 2·bit0 + 2·bit1)
///       20     4  uint32 reserved, 0
///       24     8  uint64 number of samples N (≥ 0)
///       32        N records, each the doubles, in order:
///                 time_s, lat_rad, lon_rad, height_m, speed_m_s,
///                 lgu_11, lgu_12, lgu_13, lgu_21, …, lgu_33   (C_b^n of LGU/GNSS, row by row),
///                 ins_11, …, ins_33                           (C_b^{n′} of INS/GNSS),
///                 [model_eta_rad, model_xi_rad]               (flags bit 0),
///                 [truth_eta_rad, truth_xi_rad]               (flags bit 1)
///
/// The file ends right after record N−1: a file shorter than 32 + N × record size is truncated
/// and named so with the index of the first incomplete sample; bytes after it are an error too.
/// Frames, rows E-N-U and signs as dov_files.hpp and dov/attitude_difference.hpp.
///
/// Errors (all InputError with the source as the file and "sample k" as the field, or
/// ParseError for the header): bad magic, unsupported version, unknown flag bits or a record
/// size that does not match them; a truncated file or trailing bytes; a value that is not
/// finite; a latitude beyond ±π/2. The workflow's own checks (time order, orthogonality …)
/// are dov::process's.

#include <array>
#include <cstddef>
#include <cstdint>
#include <istream>
#include <string>
#include <vector>

#include "meridian/dov/deflection.hpp"

namespace meridian::io {

inline constexpr std::array<char, 8> kDovBinaryMagic = {'M', 'R', 'D', 'N', '-', 'D', 'O', 'V'};
inline constexpr std::uint32_t kDovBinaryVersion = 1;
inline constexpr std::size_t kDovBinaryHeaderBytes = 32;
inline constexpr std::uint32_t kDovBinaryHasModel = 1u;  ///< flags bit 0
inline constexpr std::uint32_t kDovBinaryHasTruth = 2u;  ///< flags bit 1

/// True when `head` (the first bytes of a file, at least 8 of them) starts with the magic.
bool is_dov_binary(const char* head, std::size_t size);

/// The 32-byte header for `count` samples.
std::string dov_binary_header(std::uint64_t count, bool has_model, bool has_truth);

/// Append one record (the layout above) to `out`; `truth` must be given exactly when
/// has_truth. The model values are written when has_model.
void append_dov_binary_record(std::string& out, const dov::Sample& s, const dov::Truth* truth,
                              bool has_model, bool has_truth);

/// The whole line of `input` (model values always, truth when input.truth is not empty).
std::string dov_line_binary(const dov::Input& input);

/// Reads a binary line sample by sample from a stream (no seeking: pipes work).
class DovBinaryReader {
 public:
  /// Reads and checks the header now; `source` names the file in errors.
  DovBinaryReader(std::istream& in, std::string source);

  std::uint64_t count() const { return count_; }  ///< N of the header
  bool has_model() const { return (flags_ & kDovBinaryHasModel) != 0; }
  bool has_truth() const { return (flags_ & kDovBinaryHasTruth) != 0; }
  std::uint64_t samples_read() const { return read_; }
  const std::string& source() const { return source_; }

  /// Read up to `max` (≥ 1) samples, appending to `samples` (and to `truth` when the file has
  /// truth; `truth` may be null otherwise, its full state is never set). Returns the number
  /// read, 0 at the end — after checking that nothing follows the last record. Without the
  /// model columns the model values are NaN (a gravity model fills them, dov_files.hpp).
  std::size_t next(std::vector<dov::Sample>& samples, std::vector<dov::Truth>* truth,
                   std::size_t max);

 private:
  std::istream& in_;
  std::string source_;
  std::uint32_t flags_ = 0;
  std::size_t record_doubles_ = 0;
  std::uint64_t count_ = 0;
  std::uint64_t read_ = 0;
  std::vector<char> buffer_;
};

}  // namespace meridian::io
