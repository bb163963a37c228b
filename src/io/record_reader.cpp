#include "meridian/io/record_reader.hpp"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "meridian/core/dms.hpp"
#include "input_limits.hpp"

namespace meridian::io {
namespace {

constexpr std::string_view kBlanks = " \t\r\v\f";

std::string_view trim(std::string_view s) {
  const auto b = s.find_first_not_of(kBlanks);
  if (b == std::string_view::npos) return {};
  return s.substr(b, s.find_last_not_of(kBlanks) - b + 1);
}

bool is_letter(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }

char lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

bool same_name(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (lower(a[i]) != lower(b[i])) return false;
  return true;
}

bool is_bracketed_unit(std::string_view f) {
  return f.size() >= 2 && f.front() == '[' && f.back() == ']';
}

std::string column_list(const std::vector<Column>& cs) {
  std::string s;
  for (const auto& c : cs) s += (s.empty() ? "" : ", ") + c.name;
  return s;
}

void split(Delimiter delimiter, std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  if (delimiter == Delimiter::Whitespace) {
    std::size_t i = 0;
    while (true) {
      i = line.find_first_not_of(kBlanks, i);
      if (i == std::string_view::npos) return;
      const auto e = line.find_first_of(kBlanks, i);
      out.push_back(line.substr(i, e == std::string_view::npos ? std::string_view::npos : e - i));
      if (e == std::string_view::npos) return;
      i = e;
    }
  }
  const char d = delimiter == Delimiter::Comma ? ',' : ';';
  std::size_t b = 0;
  while (true) {
    const auto e = line.find(d, b);
    out.push_back(
        trim(line.substr(b, e == std::string_view::npos ? std::string_view::npos : e - b)));
    if (e == std::string_view::npos) return;
    b = e + 1;
  }
}

// Comma if the line has one, else semicolon if it has one, else whitespace.
Delimiter detect_delimiter(std::string_view line) {
  return line.find(',') != std::string_view::npos   ? Delimiter::Comma
         : line.find(';') != std::string_view::npos ? Delimiter::Semicolon
                                                    : Delimiter::Whitespace;
}

}  // namespace

Column parse_column(std::string_view text) {
  text = trim(text);
  const auto open = text.find('[');
  Column c{std::string(trim(text.substr(0, open))), ""};
  if (c.name.empty()) throw ParseError(fmt::format("header field \"{}\" has no name", text));
  if (open == std::string_view::npos) {
    if (text.find(']') != std::string_view::npos)
      throw ParseError(fmt::format("header field \"{}\" has a \"]\" without \"[\"", text));
    return c;
  }
  const auto close = text.find(']', open);
  if (close == std::string_view::npos)
    throw ParseError(fmt::format("header field \"{}\": the unit's \"[\" is not closed", text));
  if (close + 1 != text.size())
    throw ParseError(fmt::format("header field \"{}\": text after the unit's \"]\"", text));
  c.unit = std::string(trim(text.substr(open + 1, close - open - 1)));
  return c;
}

std::optional<double> to_finite_double(std::string_view text) noexcept {
  // from_chars takes no leading '+'; a sign after it ("+-1") stays invalid.
  if (!text.empty() && text.front() == '+') {
    text.remove_prefix(1);
    if (!text.empty() && (text.front() == '-' || text.front() == '+')) return std::nullopt;
  }
  if (text.empty()) return std::nullopt;
  double v = 0;
  const auto r =
      std::from_chars(text.data(), text.data() + text.size(), v, std::chars_format::general);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size() || !std::isfinite(v))
    return std::nullopt;
  return v;
}

// ------------------------------------------------------------------ Record

std::size_t Record::size() const noexcept {
  return chunk_->first_field_[index_ + 1] - chunk_->first_field_[index_];
}

std::string_view Record::field(std::size_t column) const {
  if (column >= size())
    throw InputError(
        fmt::format("missing: the line has only {} field{}", size(), size() == 1 ? "" : "s"),
        context(column));
  const std::size_t k = chunk_->first_field_[index_] + column;
  const std::size_t begin = k == 0 ? 0 : chunk_->field_end_[k - 1];
  return std::string_view(chunk_->text_).substr(begin, chunk_->field_end_[k] - begin);
}

int Record::line() const noexcept { return chunk_->lines_[index_]; }

const std::string& Record::source() const noexcept { return chunk_->source(); }

std::string Record::field_name(std::size_t column) const {
  const auto& cs = chunk_->columns();
  return column < cs.size() ? cs[column].name : fmt::format("column {}", column + 1);
}

ErrorContext Record::context(std::size_t column, FieldLabel label) const {
  return {source(), line(), label.field.empty() ? field_name(column) : std::string(label.field)};
}

ErrorContext Record::context() const { return {source(), line(), ""}; }

void Record::add_context(Error& e, std::size_t column, FieldLabel label) const {
  const bool named = !e.context().field.empty();
  e.add_context(source(), line(), named ? std::string() : context(column, label).field);
}

double Record::number(std::size_t column, FieldLabel label) const {
  const std::string_view text = field(column);
  if (const auto v = to_finite_double(text)) return *v;
  throw ParseError(
      fmt::format("{}{}\"{}\" is not a number", label.noun, label.noun.empty() ? "" : " ", text),
      context(column, label));
}

Angle Record::angle(std::size_t column, FieldLabel label) const {
  return parse(
      column, [](std::string_view t) { return parse_angle(t); }, label);
}

// ------------------------------------------------------------- RecordChunk

const std::string& RecordChunk::source() const noexcept {
  static const std::string none;
  return layout_ ? layout_->source : none;
}

const std::vector<Column>& RecordChunk::columns() const noexcept {
  static const std::vector<Column> none;
  return layout_ ? layout_->columns : none;
}

void RecordChunk::clear() {
  text_.clear();
  field_end_.clear();
  first_field_.assign(1, 0);
  lines_.clear();
}

// ------------------------------------------------------------ RecordReader

RecordReader::RecordReader(std::istream& in, std::string source, RecordFormat format)
    : in_(in),
      layout_(std::make_shared<RecordChunk::Layout>(RecordChunk::Layout{std::move(source), {}})),
      format_(format),
      delimiter_(format.delimiter) {}

// One physical line without its line end; false at the end of the stream.
bool RecordReader::read_line(std::string& out) {
  if (!detail::getline_bounded(in_, out, source(), line_ == INT_MAX ? line_ : line_ + 1)) {
    if (in_.bad()) throw IoError("cannot read the input", {source(), line_, ""});
    return false;
  }
  if (line_ == INT_MAX) throw InputError("more than 2147483647 lines", {source(), line_, ""});
  ++line_;
  bytes_ += out.size() + (in_.eof() ? 0 : 1);
  if (line_ == 1 && out.starts_with("\xEF\xBB\xBF")) out.erase(0, 3);
  return true;
}

// The next line with fields, its comment and line end removed.
bool RecordReader::next_content_line(std::string& out, int& line) {
  while (read_line(out)) {
    if (const auto hash = out.find('#'); hash != std::string::npos) out.erase(hash);
    if (out.find_first_not_of(kBlanks) == std::string::npos) continue;
    line = line_;
    return true;
  }
  return false;
}

// Read up to the first data line: decide the header and the delimiter.
void RecordReader::start() {
  started_ = true;
  std::string first;
  int first_line = 0;
  if (!next_content_line(first, first_line)) {
    if (format_.header == HeaderMode::Present)
      throw ParseError("no header line: the input has no line of column names",
                       {source(), std::nullopt, ""});
    return;
  }
  const std::string_view t = trim(first);
  bool header = format_.header == HeaderMode::Present;
  if (format_.header == HeaderMode::Auto && is_letter(t.front())) {
    std::vector<std::string_view> f;
    split(delimiter_ == Delimiter::Auto ? detect_delimiter(t) : delimiter_, t, f);
    header = std::all_of(f.begin(), f.end(), [](std::string_view x) {
      return !x.empty() && (is_letter(x.front()) || is_bracketed_unit(x));
    });
  }
  if (header) {
    header_line_ = first_line;
    std::string data;
    int data_line = 0;
    if (next_content_line(data, data_line)) pending_.emplace(std::move(data), data_line);
  } else {
    pending_.emplace(std::move(first), first_line);
  }
  if (delimiter_ == Delimiter::Auto)
    delimiter_ = detect_delimiter(pending_ ? std::string_view(pending_->first) : t);
  if (!header) return;
  std::vector<std::string_view> f;
  split(delimiter_, t, f);
  auto& cols = layout_->columns;
  for (std::size_t i = 0; i < f.size(); ++i) {
    // A unit standing apart ("lat [deg]" split on whitespace) joins its name.
    if (delimiter_ == Delimiter::Whitespace && is_bracketed_unit(f[i]) && !cols.empty() &&
        cols.back().unit.empty()) {
      cols.back().unit = std::string(trim(f[i].substr(1, f[i].size() - 2)));
      continue;
    }
    try {
      cols.push_back(parse_column(f[i]));
    } catch (Error& e) {
      e.add_context(source(), header_line_, fmt::format("column {}", i + 1));
      throw;
    }
    for (std::size_t j = 0; j + 1 < cols.size(); ++j)
      if (same_name(cols[j].name, cols.back().name))
        throw ParseError(fmt::format("column \"{}\" appears twice in the header", cols.back().name),
                         {source(), header_line_, ""});
  }
}

const std::vector<Column>& RecordReader::header() {
  if (!started_) start();
  return layout_->columns;
}

int RecordReader::header_line() {
  header();
  return header_line_;
}

namespace {

// The bracketed units that say the same as a column name's unit suffix ("speed_m_s" and
// [m/s]); empty when the name carries no suffix this table knows.
std::vector<std::string_view> units_of_suffix(std::string_view name) {
  struct Suffix {
    std::string_view suffix;
    std::vector<std::string_view> units;
  };
  static const std::vector<Suffix> table = {
      {"_m_s", {"m/s", "m_s", "m s-1", "m s^-1"}},   {"_m_s2", {"m/s2", "m/s^2", "m_s2"}},
      {"_m", {"m"}},                                 {"_s", {"s"}},
      {"_deg", {"deg", "°", "degrees"}},             {"_rad", {"rad"}},
      {"_arcsec", {"arcsec", "\"", "″"}},            {"_mgal", {"mGal", "mgal"}},
      {"_deg_h", {"deg/h", "°/h"}},                  {"_a", {"A"}},
  };
  const Suffix* best = nullptr;
  for (const Suffix& x : table)
    if (name.size() > x.suffix.size() &&
        same_name(name.substr(name.size() - x.suffix.size()), x.suffix) &&
        (!best || x.suffix.size() > best->suffix.size()))
      best = &x;
  return best ? best->units : std::vector<std::string_view>{};
}

}  // namespace

std::optional<std::size_t> RecordReader::find_column(std::string_view name) {
  const auto& cs = header();
  for (std::size_t i = 0; i < cs.size(); ++i)
    if (same_name(cs[i].name, name)) {
      // The one unit rule (issue 35): a column found by a name that states its unit must not
      // carry another unit in brackets ("speed_m_s [kn]" was read as m/s): refused, never ignored.
      if (!cs[i].unit.empty()) {
        const auto units = units_of_suffix(name);
        const bool same = std::any_of(units.begin(), units.end(), [&](std::string_view u) { return u == cs[i].unit; });
        if (!units.empty() && !same)
          throw InputError(fmt::format("column {} [{}]: its name gives the unit {} and the brackets {}; write "
                                       "the values in {} (Meridian converts no units here)",
                                       cs[i].name, cs[i].unit, units.front(), cs[i].unit, units.front()),
                           {source(), header_line_, cs[i].name});
      }
      return i;
    }
  return std::nullopt;
}

std::size_t RecordReader::require_column(std::string_view name) {
  if (const auto i = find_column(name)) return *i;
  const auto& cs = header();
  if (cs.empty())
    throw InputError(
        fmt::format("no column \"{}\": the input has no header line of column names", name),
        {source(), std::nullopt, ""});
  throw InputError(
      fmt::format("no column \"{}\" in the header (columns: {})", name, column_list(cs)),
      {source(), header_line_, ""});
}

bool RecordReader::next(RecordChunk& chunk, std::size_t max_records) {
  if (max_records == 0)
    throw InputError("a chunk must hold at least one record", {source(), std::nullopt, ""});
  if (!started_) start();
  chunk.clear();
  chunk.layout_ = layout_;
  auto add = [&](std::string_view line, int line_no) {
    split(delimiter_, line, fields_);
    for (auto f : fields_) {
      chunk.text_.append(f);
      chunk.field_end_.push_back(chunk.text_.size());
    }
    chunk.first_field_.push_back(chunk.field_end_.size());
    chunk.lines_.push_back(line_no);
  };
  if (pending_) {
    add(pending_->first, pending_->second);
    pending_.reset();
  }
  int line_no = 0;
  while (chunk.size() < max_records && next_content_line(buffer_, line_no)) add(buffer_, line_no);
  return !chunk.empty();
}

}  // namespace meridian::io
