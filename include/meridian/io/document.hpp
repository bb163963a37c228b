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

#include <yaml-cpp/yaml.h>

#include "meridian/core/angle.hpp"
#include "meridian/core/dms.hpp"
#include "meridian/core/error.hpp"

namespace meridian::io {

/// Line (1-based) of each node of a file by field path ("determinations[2]",
/// "line.determinations[0].crossings[1]", …), as recorded while reading.
/// A runner hands them to io::SourceMap (source_map.hpp), which names the line of an error.
using FieldLines = std::map<std::string, int>;

/// One node of a YAML or JSON document (JSON is read by the YAML parser as
/// is). Accessors check the type and range and throw ParseError/InputError
/// with file, line and field path. Copies share the document.

class Node {
 public:
  using LineMap = FieldLines;

  Node(YAML::Node node, std::string path, std::shared_ptr<const std::string> file,
       std::shared_ptr<LineMap> lines);
  Node(const Node&) = default;
  // YAML::Node's assignment writes through to the document; rebind instead.
  Node& operator=(const Node& o) {
    node_.reset(o.node_);
    path_ = o.path_;
    file_ = o.file_;
    lines_ = o.lines_;
    return *this;
  }

  /// Load a YAML or JSON file (JSON is read by the YAML parser as is).
  /// A syntax error on a line indented with a tab is reported as "tabs are
  /// not allowed for indentation (line N)" (YAML forbids them; JSON's tabs,
  /// which are allowed, never cause a syntax error).
  static Node load_file(const std::filesystem::path& path);

  const std::string& path() const { return path_; }
  const std::string& file() const { return *file_; }
  /// Line of every node visited so far, by field path.
  const LineMap& visited_lines() const { return *lines_; }
  int line() const;  ///< 1-based

  bool is_map() const { return node_.IsMap(); }
  bool is_sequence() const { return node_.IsSequence(); }
  bool is_scalar() const { return node_.IsScalar(); }

  /// Member `key`; nullopt when absent. Requires a map. Throws InputError (file, line, field)
  /// when the key is present without a value (YAML null: "key:", "key: ~", "key: null"), so a
  /// forgotten value is never replaced by a default.
  std::optional<Node> get(const std::string& key) const;
  /// Member `key`; throws "missing field" when absent, InputError as get() when null.
  Node require(const std::string& key) const;
  bool has(const std::string& key) const { return get(key).has_value(); }

  /// Elements of a sequence (a scalar is not accepted).
  std::vector<Node> elements() const;

  double number() const;           ///< a finite number
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
  YAML::Node node_;
  std::string path_;
  std::shared_ptr<const std::string> file_;
  std::shared_ptr<LineMap> lines_;
};

}  // namespace meridian::io
