#include "meridian/io/document.hpp"

#include <cmath>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "meridian/core/dms.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/utf8.hpp"

namespace meridian::io {
namespace {

// The whole scalar as a number (possibly not finite); nullopt when it is not one.
std::optional<double> whole_number(const std::string& s) {
  double v = 0;
  std::size_t used = 0;
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  while (used < s.size() && std::isspace(static_cast<unsigned char>(s[used]))) ++used;
  if (used != s.size()) return std::nullopt;
  return v;
}

// `s` with every byte outside printable ASCII shown as \xHH, for messages.
std::string printable(const std::string& s) {
  std::string out;
  for (const char ch : s) {
    const auto b = static_cast<unsigned char>(ch);
    if (b >= 0x20 && b < 0x7F) out += ch;
    else out += fmt::format("\\x{:02X}", b);
  }
  return out;
}

}  // namespace

Node::Node(std::shared_ptr<const DocumentTree> root, const DocumentTree* node, std::string path,
           std::shared_ptr<const std::string> file, std::shared_ptr<LineMap> lines)
    : root_(std::move(root)), node_(node), path_(std::move(path)), file_(std::move(file)), lines_(std::move(lines)) {
  if (node_->line > 0) (*lines_)[path_] = node_->line;
}

int Node::line() const { return node_->line; }

std::optional<int> Node::mark_line() const {
  return node_->line > 0 ? std::optional<int>(node_->line) : std::nullopt;
}

void Node::locate(Error& e) const { e.add_context(*file_, mark_line(), path_); }

void Node::fail(const std::string& message) const {
  throw InputError(message, {*file_, mark_line(), path_});
}

std::string Node::child_path(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

std::optional<Node> Node::get(const std::string& key) const {
  if (!is_map()) fail("expected a mapping of fields");
  const DocumentTree::Member* m = nullptr;
  for (const auto& c : node_->members)
    if (c.key == key) {
      m = &c;
      break;
    }
  if (!m) return std::nullopt;
  // A key written without a value ("sigma_arcsec:") is null in YAML: taking the default for it
  // would hide a value the user meant to give (trial finding), so it is an error.
  if (m->value.kind == DocumentTree::Kind::Null) {
    // The key's own line (an empty value's mark is the next one).
    const std::optional<int> line = m->key_line > 0 ? std::optional<int>(m->key_line) : mark_line();
    throw InputError(fmt::format("\"{}\" has no value: give one (or remove the line, where the field has a default)", key),
                     {*file_, line, child_path(key)});
  }
  return Node(root_, &m->value, child_path(key), file_, lines_);
}

Node Node::require(const std::string& key) const {
  auto c = get(key);
  if (!c) throw InputError(fmt::format("missing field \"{}\"", key), {*file_, mark_line(), child_path(key)});
  return *c;
}

std::vector<Node> Node::elements() const {
  if (!is_sequence()) fail("expected a list");
  std::vector<Node> out;
  std::size_t i = 0;
  for (const auto& c : node_->elements) out.emplace_back(root_, &c, fmt::format("{}[{}]", path_, i++), file_, lines_);
  return out;
}

double Node::number() const {
  if (!is_scalar()) fail("expected a number");
  const std::string& s = node_->scalar;
  const auto v = whole_number(s);
  if (!v) fail(fmt::format("expected a number, got \"{}\"", s));
  if (!std::isfinite(*v)) fail(fmt::format("expected a finite number, got \"{}\"", s));
  // No quantity a job or book holds comes near this in any unit; such a value is a slip, and a
  // sigma of 1e200 overflowed when squared and was blamed on a data file's line (issue 35).
  if (std::fabs(*v) > kMaxDocumentNumber)
    fail(fmt::format("{} is beyond any value Meridian reads (|x| <= 1e30 in the field's unit): a slip?", s));
  return *v;
}

double Node::positive_number() const {
  const double v = number();
  if (!(v > 0)) fail(fmt::format("must be positive (got {})", v));
  return v;
}

double Node::non_negative_number() const {
  const double v = number();
  if (v < 0) fail(fmt::format("must not be negative (got {})", v));
  return v;
}

int Node::integer() const {
  const double v = number();
  if (v != std::floor(v) || std::fabs(v) > 1e9) fail(fmt::format("expected a whole number (got {})", v));
  return static_cast<int>(v);
}

bool Node::boolean() const {
  if (!is_scalar()) fail("expected true or false");
  const std::string& s = node_->scalar;
  // YAML 1.2's core schema (true, True, TRUE) and the YAML 1.1 yes/no that files still use.
  for (const char* t : {"true", "True", "TRUE", "yes", "Yes", "YES"})
    if (s == t) return true;
  for (const char* f : {"false", "False", "FALSE", "no", "No", "NO"})
    if (s == f) return false;
  fail(fmt::format("expected true or false (or yes, no), got \"{}\"", s));
}

std::string Node::string() const {
  if (!is_scalar()) fail("expected a text value");
  const std::string& s = node_->scalar;
  // Text goes on into JSON and HTML, which need UTF-8: say where it is not.
  if (const auto bad = first_invalid_utf8(s))
    fail(fmt::format("text is not UTF-8 (byte 0x{:02X} at position {} of \"{}\"); save the file as UTF-8",
                     static_cast<unsigned char>(s[*bad]), *bad + 1, printable(s)));
  return s;
}

Angle Node::angle() const { return angle(AngleUnit::Dms); }

Angle Node::angle(AngleUnit unit) const {
  if (!is_scalar()) {
    if (unit == AngleUnit::Dms)
      fail("expected an angle (DMS text such as \"157 21 00\" or decimal degrees)");
    fail(fmt::format("expected an angle (angle_unit {})", to_string(unit)));
  }
  const std::string& s = node_->scalar;
  try {
    return parse_angle(s, unit);
  } catch (Error& e) {
    locate(e);
    throw;
  }
}

std::vector<double> Node::numbers() const {
  std::vector<double> v;
  for (const auto& e : elements()) v.push_back(e.number());
  return v;
}

double Node::time_s() const {
  if (!is_scalar()) fail("expected a time (seconds, or a stopwatch reading m:ss.s)");
  const std::string& s = node_->scalar;
  if (whole_number(s)) return number();  // a number keeps its rules (finite)
  try {
    return parse_stopwatch_s(s);
  } catch (Error& e) {
    locate(e);
    throw;
  }
}

std::vector<double> Node::times_s() const {
  std::vector<double> v;
  for (const auto& e : elements()) v.push_back(e.time_s());
  return v;
}

void Node::allow_only(std::initializer_list<std::string_view> allowed) const {
  if (!is_map()) fail("expected a mapping of fields");
  std::set<std::string> seen;
  for (const auto& m : node_->members) {
    const std::string& key = m.key;
    const auto fail_key = [&](const std::string& message) {
      throw InputError(message, {*file_, m.key_line > 0 ? std::optional<int>(m.key_line) : mark_line(), child_path(key)});
    };
    if (m.key_line > 0) (*lines_)[child_path(key)] = m.key_line;
    if (!seen.insert(key).second) fail_key("duplicate field");
    bool ok = false;
    for (auto a : allowed) ok = ok || a == key;
    if (!ok) {
      std::string list;
      for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      fail_key(fmt::format("unknown field \"{}\" (accepted here: {})", key, list));
    }
  }
}

}  // namespace meridian::io
