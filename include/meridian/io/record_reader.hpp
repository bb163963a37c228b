#pragma once
/// \file record_reader.hpp
/// A streaming reader of delimited text records (CSV, semicolon- or
/// whitespace-separated columns) from a std::istream — a file or stdin —
/// a chunk of records at a time, so a survey line of millions of rows never
/// sits in memory. Workflow readers (io/gravity_points.hpp, later the
/// navigation and deflection lines) are built on it; it knows no workflow.
///
/// Format (docs/file-formats.md, "Delimited text records"):
/// * one record per line; LF or CRLF line ends; a UTF-8 byte-order mark at
///   the start of the stream is ignored;
/// * `#` starts a comment that runs to the end of the line, on a line of its
///   own or after the fields; blank lines and comment lines are skipped but
///   counted, so line numbers are those of the file (1-based);
/// * fields are separated by a comma, a semicolon, or runs of spaces and
///   tabs (Delimiter). With Delimiter::Auto the first data line decides:
///   a comma if it has one, else a semicolon if it has one, else whitespace.
///   Fields are trimmed of spaces and tabs; with a comma or semicolon an
///   empty field is kept as "" (`1,,3` has three fields);
/// * quoting is NOT supported: `"` is an ordinary character, and a field
///   cannot contain the delimiter, `#` or a line end. With whitespace as the
///   delimiter a field cannot contain spaces either (write DMS angles as
///   `37:50:24` or `37d50m24s`, or use commas);
/// * an optional header line of column names, the first line that is not
///   blank or a comment (HeaderMode). With HeaderMode::Auto it is a header
///   when every field of it is non-empty and begins with a letter (A–Z,
///   a–z) — a data line has at least one number, which begins with a
///   digit, a sign or a point. A name may carry its unit in square brackets
///   after it: `lat [deg]`, `h[m]`, `dg [mGal]` give the names lat, h, dg and
///   the units deg, m, mGal (Column). With whitespace as the delimiter a
///   bracketed unit may stand apart (`lat [deg] lon [deg]`): a field that is
///   a bracketed unit alone belongs to the name before it. Underscore
///   suffixes (`lat_deg`) are part of the name and give no unit. Names must
///   be unique (compared without regard to ASCII case).
///
/// Records do not have to have as many fields as the header: the workflow
/// reader decides what it accepts, with the errors this header's helpers
/// throw. Every error names the source (file name or "<stdin>"), the 1-based
/// line and the field, e.g. `points.csv:17: h_m: "5x" is not a number`.

#include <cstddef>
#include <cstdint>
#include <istream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "meridian/core/angle.hpp"
#include "meridian/core/error.hpp"

namespace meridian::io {

/// How fields are separated.
enum class Delimiter {
  Auto,        ///< decided from the first data line (see the file comment)
  Comma,       ///< `,`
  Semicolon,   ///< `;`
  Whitespace,  ///< runs of spaces and tabs
};

/// Whether the first line that is not blank or a comment names the columns.
enum class HeaderMode {
  Auto,     ///< a header when every field is non-empty and begins with a letter
  Present,  ///< always a header (an input without any line is then an error)
  Absent,   ///< never a header: every line is data
};

struct RecordFormat {
  Delimiter delimiter = Delimiter::Auto;
  HeaderMode header = HeaderMode::Auto;
};

/// One column named by the header: `lat [deg]` → {"lat", "deg"}.
struct Column {
  std::string name;  ///< without the unit, trimmed
  std::string unit;  ///< inside the brackets, trimmed; empty when none is given
};

/// Split one header field into name and unit (the bracket convention
/// above). Throws ParseError (no context) for an empty name, an unclosed
/// `[`, or text after the `]`.
Column parse_column(std::string_view text);

/// The text as a finite double in decimal notation (`12`, `-0.5`, `+3e-4`,
/// `.5`; no hexadecimal, no surrounding spaces); nullopt for anything else,
/// including NaN and infinity.
std::optional<double> to_finite_double(std::string_view text) noexcept;

/// How a field is named in an error (Record::number, Record::angle, Record::parse).
struct FieldLabel {
  /// The field in the error context; empty: the column's name, else "column N".
  std::string_view field = {};
  /// Record::number only: put before the quoted text ("height" gives
  /// `height "5x" is not a number`).
  std::string_view noun = {};
};

class RecordChunk;

/// One record of a chunk: its trimmed fields and its line. A view: valid
/// while its chunk is alive and not refilled.
class Record {
 public:
  /// Number of fields on the line (≥ 1).
  std::size_t size() const noexcept;
  /// The trimmed text of field `column` (0-based). Throws InputError with
  /// this record's context when the line has fewer fields.
  std::string_view field(std::size_t column) const;
  std::string_view operator[](std::size_t column) const { return field(column); }
  /// 1-based line in the source.
  int line() const noexcept;
  /// File name (or "<stdin>") given to the reader.
  const std::string& source() const noexcept;

  /// The name of a column in errors: its header name, else "column N" (1-based).
  std::string field_name(std::size_t column) const;
  /// {source, line, label.field or field_name(column)}: for errors about one field.
  ErrorContext context(std::size_t column, FieldLabel label = {}) const;
  /// {source, line, no field}: for errors about the whole record.
  ErrorContext context() const;

  /// Field `column` as a finite double (to_finite_double). Throws
  /// ParseError `"<text>" is not a number` (with label.noun before the
  /// quote when given) in this record's context.
  double number(std::size_t column, FieldLabel label = {}) const;
  /// Field `column` as an angle: DMS or decimal degrees, and every other
  /// form core/dms.hpp parse_angle reads. Throws parse_angle's ParseError in
  /// this record's context.
  Angle angle(std::size_t column, FieldLabel label = {}) const;
  /// `parse(field(column))` for any parser of field text; an Error it throws
  /// gets this record's source, line and the field (label.field or the
  /// column's name) when it has none of its own.
  template <class Parse>
  auto parse(std::size_t column, Parse&& parse_text, FieldLabel label = {}) const {
    const std::string_view text = field(column);
    try {
      return parse_text(text);
    } catch (Error& e) {
      add_context(e, column, label);
      throw;
    }
  }

 private:
  friend class RecordChunk;
  Record(const RecordChunk* chunk, std::size_t index) : chunk_(chunk), index_(index) {}
  void add_context(Error& e, std::size_t column, FieldLabel label) const;
  const RecordChunk* chunk_;
  std::size_t index_;
};

/// Records read by one RecordReader::next call. Fields are stored back to
/// back in one buffer that is reused from chunk to chunk, so reading
/// allocates nothing once the buffers have grown to a chunk's size.
class RecordChunk {
 public:
  std::size_t size() const noexcept { return lines_.size(); }
  bool empty() const noexcept { return lines_.empty(); }
  /// Record i (0-based within the chunk), i < size().
  Record operator[](std::size_t i) const { return Record(this, i); }
  /// File name (or "<stdin>") given to the reader.
  const std::string& source() const noexcept;
  /// The header's columns; empty when the input has no header.
  const std::vector<Column>& columns() const noexcept;

 private:
  friend class Record;
  friend class RecordReader;
  struct Layout {
    std::string source;
    std::vector<Column> columns;
  };
  void clear();
  std::string text_;                    // every field's text, back to back
  std::vector<std::size_t> field_end_;  // end of each field in text_
  // Per record, the index of its first field in field_end_; one extra at the end.
  std::vector<std::size_t> first_field_;
  std::vector<int> lines_;  // per record
  std::shared_ptr<const Layout> layout_;
};

/// Reads records from a stream a chunk at a time. Not copyable; reads the
/// stream sequentially (no seeking, so pipes work).
class RecordReader {
 public:
  /// `source` names the input in errors ("points.csv", "<stdin>"). The
  /// stream is read lazily, on the first call of next() or header().
  RecordReader(std::istream& in, std::string source, RecordFormat format = {});
  RecordReader(const RecordReader&) = delete;
  RecordReader& operator=(const RecordReader&) = delete;

  /// Replace the contents of `chunk` with the next records, at most
  /// `max_records` (≥ 1) of them, and return false when there were none
  /// left. Records are the same whatever the chunk sizes. Throws ParseError
  /// for a bad header (with HeaderMode::Present also for a missing one),
  /// IoError when the stream fails, InputError for `max_records` 0.
  bool next(RecordChunk& chunk, std::size_t max_records);

  /// The header's columns (read now if not yet read); empty without a header.
  const std::vector<Column>& header();
  /// Index of the column named `name` (without its unit; ASCII case is
  /// ignored), or nullopt when the header has none (or there is no header).
  std::optional<std::size_t> find_column(std::string_view name);
  /// As find_column, but throws InputError naming the source, the header
  /// line and the columns there are.
  std::size_t require_column(std::string_view name);

  /// Line of the header (1-based; read now if not yet read); 0 without a header.
  int header_line();
  /// The delimiter in use: Auto until the first data line has been read.
  Delimiter delimiter() const noexcept { return delimiter_; }
  /// Bytes consumed from the stream so far (line ends included); for progress.
  std::uint64_t bytes_read() const noexcept { return bytes_; }
  /// The last line read (1-based; 0 before any).
  int lines_read() const noexcept { return line_; }
  const std::string& source() const noexcept { return layout_->source; }

 private:
  bool read_line(std::string& out);
  bool next_content_line(std::string& out, int& line);
  void start();

  std::istream& in_;
  std::shared_ptr<RecordChunk::Layout> layout_;
  RecordFormat format_;
  Delimiter delimiter_;
  bool started_ = false;
  int header_line_ = 0;
  std::optional<std::pair<std::string, int>> pending_;  // first data line, read while starting
  std::string buffer_;
  std::vector<std::string_view> fields_;
  std::uint64_t bytes_ = 0;
  int line_ = 0;
};

}  // namespace meridian::io
