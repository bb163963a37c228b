#pragma once
/// \file source_map.hpp
/// Where each field of a workflow's Input was read, so that an error the library throws with a
/// field path names the file, line and column the user wrote. The one error-locating mechanism
/// of every runner (docs/architecture.md, "Errors").
///
/// The library knows only its Input: it throws `InputError("is negative", {"", {}, "dr[12].speed_m_s"})`.
/// The reader knows where `dr[12]` came from. A runner collects what its readers recorded in one
/// SourceMap and calls `located(sources, [&] { return process(input); })`; the error leaves as
///
///     dr.csv:14: speed: is negative
///
/// with its class kept (InputError stays InputError, ParseError stays ParseError, so the exit code
/// is the same). An error that names a file already (a reader's own) passes unchanged.
///
/// Example (a job file with a CSV of rows beside it):
///
///     io::SourceMap sources;
///     sources.add_document("", job.file, job.lines);           // "options.x" → job.yaml:LINE: options.x
///     sources.add_rows("dr", dr_rows, [](const std::string& m) { return m == "speed_m_s" ? "speed" : m; });
///     nav::Result r = io::located(sources, [&] { return nav::process(input); });

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "meridian/core/error.hpp"
#include "meridian/io/document.hpp"

namespace meridian::io {

/// One row of a delimited-text file: its file and 1-based line.
struct SourceRow {
  std::string file;
  int line = 0;
};

/// A field path's place in the user's files, built by the readers of one job.
///
/// Rules are matched by the longest field prefix; a prefix matches a field that equals it or
/// continues with '.', '[' or ' '. Row rules read the element index that follows their prefix
/// ("dr[12].speed_m_s", "samples[40]", "epoch 40: …", "position1.time_s[7]").
class SourceMap {
 public:
  /// The member name of a row as the user wrote it (the CSV column); empty: name no column.
  using ColumnOf = std::function<std::string(const std::string& member)>;
  /// For rows too many to keep (a streamed line): the place of row `index`, member `member`
  /// (empty when the field names no member).
  using RowLocator = std::function<ErrorContext(std::size_t index, const std::string& member)>;

  /// Keys of a YAML/JSON document (io::Node's visited lines). A field under `field_prefix` is
  /// located at the line of the innermost recorded key that contains it, after `field_prefix` is
  /// replaced by `key_prefix` ("options.sigma_m" with field_prefix "options" and key_prefix ""
  /// is the document's key "sigma_m"); the error's field becomes that key path. An empty
  /// field_prefix matches every field (the document of the job itself).
  void add_document(std::string field_prefix, std::string file, FieldLines lines, std::string key_prefix = {});
  void add_document(std::string file, FieldLines lines) { add_document({}, std::move(file), std::move(lines)); }

  /// Rows of an array read from delimited text: "array[i].member" is rows[i]'s file and line,
  /// with the field column(member) (the member itself when `column` is empty). An index beyond
  /// the rows is located by the other rules.
  void add_rows(std::string array, std::vector<SourceRow> rows, ColumnOf column = {});
  /// The same for a stream: `locate(i, member)` gives the place.
  void add_rows(std::string array, RowLocator locate);

  /// One place for every field under `field_prefix` (a value read from one line of a file);
  /// the error's field becomes `field` (empty: none).
  void add_place(std::string field_prefix, ErrorContext where);

  /// Give `e` the place of its field. Leaves errors that already name a file, or name no field,
  /// unchanged; a field no rule matches keeps its path and gets no file.
  void locate(Error& e) const;

  /// The place of a field path by the same rules (for a result that names the field it is
  /// about, such as a failed check); std::nullopt when no rule matches. An empty field is the
  /// job's document.
  std::optional<ErrorContext> place(const std::string& field) const;

 private:
  enum class Kind { Document, Rows, Place };
  struct Rule {
    Kind kind;
    std::string prefix;
    // Document
    std::string file;
    FieldLines lines;
    std::string key_prefix;
    // Rows
    std::vector<SourceRow> rows;
    ColumnOf column;
    RowLocator row_locator;
    // Place
    ErrorContext place;
  };
  std::optional<ErrorContext> resolve(const Rule& r, const std::string& field) const;
  std::vector<Rule> rules_;
};

/// Run `body`, giving any meridian::Error it throws the place of its field (SourceMap::locate)
/// and rethrowing it with its class.
template <class F>
decltype(auto) located(const SourceMap& sources, F&& body) {
  try {
    return body();
  } catch (Error& e) {
    sources.locate(e);
    throw;
  }
}

}  // namespace meridian::io
