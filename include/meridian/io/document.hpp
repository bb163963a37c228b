#pragma once
/// \file document.hpp
/// A YAML/JSON document whose every node knows its file, line and field
/// path, so every error names where the bad value is
/// ("campaign.yaml:41: line.determinations[1].crossings[0].times_s: …").
/// Workflow readers (io/gyro_files.hpp, later io/nav_*, io/dov_*) are built on
/// it; it knows no workflow.

#include <filesystem>
#include <initializer_list>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "meridian/core/angle.hpp"
#include "meridian/core/dms.hpp"
#include "meridian/core/error.hpp"
#include "meridian/io/document_tree.hpp"

namespace meridian::io {

/// Line (1-based) of each node of a file by field path ("determinations[2]",
/// "line.determinations[0].crossings[1]", …), as recorded while reading.
/// A runner hands them to io::SourceMap (source_map.hpp), which names the line of an error.
using FieldLines = std::map<std::string, int>;

/// One node of a YAML or JSON document (JSON is read by the YAML parser as
/// is), over its DocumentTree (document_tree.hpp). Accessors check the type and range and throw ParseError/InputError
/// with file, line and field path. Copies share the document.

class Node {
 public:
  using LineMap = FieldLines;

  /// `node` within the document `root` (which it keeps alive), at field path `path`.
  Node(std::shared_ptr<const DocumentTree> root, const DocumentTree* node, std::string path,
       std::shared_ptr<const std::string> file, std::shared_ptr<LineMap> lines);

  /// Load a YAML or JSON file (JSON is read by the YAML parser as is).
  /// A syntax error on a line indented with a tab is reported as "tabs are
  /// not allowed for indentation (line N)" (YAML forbids them; JSON's tabs,
  /// which are allowed, never cause a syntax error).
  static Node load_file(const std::filesystem::path& path);
  /// Parse YAML or JSON `text` (yaml-cpp) as if read from the file named `file` (for messages):
  /// the same checks as load_file after reading (empty, NUL bytes, tabs, syntax, top level).
  static Node load_text(const std::string& text, const std::string& file);
  /// A document tree another parser made, written as JSON (nlohmann): every node an object
  /// {"kind": "null"|"scalar"|"sequence"|"map", "line": N, "scalar": "text as written",
  ///  "elements": [node…], "members": [{"key": "k", "key_line": N, "value": node}…]};
  /// `file` names it in messages. Throws ParseError for JSON that is not such a tree, and
  /// InputError when the top level is not a map.
  static Node load_tree_json(const std::string& tree_json, const std::string& file);
  /// The tree this node reads.
  const DocumentTree& tree() const { return *node_; }

  const std::string& path() const { return path_; }
  const std::string& file() const { return *file_; }
  /// Line of every node visited so far, by field path.
  const LineMap& visited_lines() const { return *lines_; }
  int line() const;  ///< 1-based

  bool is_map() const { return node_->kind == DocumentTree::Kind::Map; }
  bool is_sequence() const { return node_->kind == DocumentTree::Kind::Sequence; }
  bool is_scalar() const { return node_->kind == DocumentTree::Kind::Scalar; }

  /// Member `key`; nullopt when absent. Requires a map. Throws InputError (file, line, field)
  /// when the key is present without a value (YAML null: "key:", "key: ~", "key: null"), so a
  /// forgotten value is never replaced by a default.
  std::optional<Node> get(const std::string& key) const;
  /// Member `key`; throws "missing field" when absent, InputError as get() when null.
  Node require(const std::string& key) const;
  bool has(const std::string& key) const { return get(key).has_value(); }

  /// Elements of a sequence (a scalar is not accepted).
  std::vector<Node> elements() const;

  /// A finite number with |x| <= kMaxDocumentNumber (1e30: larger is a slip; a sigma of 1e200
  /// overflowed when squared). Fails naming the field otherwise.
  double number() const;
  double positive_number() const;  ///< a finite number > 0
  double non_negative_number() const;
  int integer() const;
  bool boolean() const;
  std::string string() const;
  /// Angle: a number is decimal degrees; a string is parsed by parse_angle
  /// (DMS, gon, …).
  Angle angle() const;
  /// Angle in a field book's unit (the file's `angle_unit:`), read from the
  /// value as written by parse_angle(text, unit); AngleUnit::Dms is angle().
  /// Throws ParseError with file, line and field.
  Angle angle(AngleUnit unit) const;
  /// Sequence of finite numbers; each element records its own line, so an
  /// error about element i (path "…[i]") is located at that element.
  std::vector<double> numbers() const;
  /// Stopwatch time in seconds: a number (read as number()), or text
  /// "m:ss.s", "h:mm:ss.s", "m′ss.s″" (parse_stopwatch_s). Anything else is
  /// a ParseError with file, line and field.
  double time_s() const;
  std::vector<double> times_s() const;  ///< sequence of time_s()

  /// Throws for keys other than `allowed` (catches typos and unknown units)
  /// and for duplicate keys.
  void allow_only(std::initializer_list<std::string_view> allowed) const;

  [[noreturn]] void fail(const std::string& message) const;

 private:
  std::string child_path(const std::string& key) const;
  std::optional<int> mark_line() const;  ///< 1-based line, when the parser knows it
  /// Give an error about this node's value its file, line and path.
  void locate(Error& e) const;
  std::shared_ptr<const DocumentTree> root_;
  const DocumentTree* node_;
  std::string path_;
  std::shared_ptr<const std::string> file_;
  std::shared_ptr<LineMap> lines_;
};

}  // namespace meridian::io
