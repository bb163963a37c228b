#include "meridian/io/source_map.hpp"

#include <algorithm>
#include <utility>

namespace meridian::io {
namespace {

// `field` equals `prefix` or continues it with '.', '[' or ' ' (an empty prefix matches all).
bool continues(const std::string& field, const std::string& prefix) {
  if (prefix.empty()) return true;
  if (field.compare(0, prefix.size(), prefix) != 0) return false;
  if (field.size() == prefix.size()) return true;
  const char c = field[prefix.size()];
  return c == '.' || c == '[' || c == ' ';
}

// The element index right after a row rule's prefix ("[12]" or " 12") and the member after it
// (".speed_m_s" → "speed_m_s").
struct RowRef {
  std::size_t index;
  std::string member;
};

std::optional<RowRef> row_ref(const std::string& field, std::size_t at) {
  if (at >= field.size() || (field[at] != '[' && field[at] != ' ')) return std::nullopt;
  const bool bracket = field[at] == '[';
  std::size_t i = at + 1, digits = 0;
  std::size_t index = 0;
  while (i < field.size() && field[i] >= '0' && field[i] <= '9' && digits < 19) {
    index = index * 10 + static_cast<std::size_t>(field[i] - '0');
    ++i, ++digits;
  }
  if (digits == 0 || digits > 18) return std::nullopt;
  if (bracket) {
    if (i >= field.size() || field[i] != ']') return std::nullopt;
    ++i;
  }
  RowRef r{index, {}};
  if (i < field.size() && field[i] == '.') r.member = field.substr(i + 1);
  return r;
}

}  // namespace

void SourceMap::add_document(std::string field_prefix, std::string file, FieldLines lines, std::string key_prefix) {
  Rule r{Kind::Document, std::move(field_prefix), std::move(file), std::move(lines), std::move(key_prefix), {}, {}, {}, {}};
  rules_.push_back(std::move(r));
}

void SourceMap::add_rows(std::string array, std::vector<SourceRow> rows, ColumnOf column) {
  Rule r{Kind::Rows, std::move(array), {}, {}, {}, std::move(rows), std::move(column), {}, {}};
  rules_.push_back(std::move(r));
}

void SourceMap::add_rows(std::string array, RowLocator locate) {
  Rule r{Kind::Rows, std::move(array), {}, {}, {}, {}, {}, std::move(locate), {}};
  rules_.push_back(std::move(r));
}

void SourceMap::add_place(std::string field_prefix, ErrorContext where) {
  Rule r{Kind::Place, std::move(field_prefix), {}, {}, {}, {}, {}, {}, std::move(where)};
  rules_.push_back(std::move(r));
}

std::optional<ErrorContext> SourceMap::resolve(const Rule& r, const std::string& field) const {
  switch (r.kind) {
    case Kind::Place:
      return r.place;
    case Kind::Rows: {
      const auto ref = row_ref(field, r.prefix.size());
      if (!ref) return std::nullopt;
      if (r.row_locator) return r.row_locator(ref->index, ref->member);
      if (ref->index >= r.rows.size()) return std::nullopt;
      const SourceRow& row = r.rows[ref->index];
      return ErrorContext{row.file, row.line, r.column ? r.column(ref->member) : ref->member};
    }
    case Kind::Document: {
      std::string rest = field.substr(r.prefix.size());
      if (r.key_prefix.empty() && !rest.empty() && rest.front() == '.') rest.erase(0, 1);
      const std::string key = r.key_prefix + rest;
      // The innermost recorded key that contains the field (io::Node records every key it visits).
      std::optional<int> line;
      std::size_t best = 0;
      for (const auto& [path, l] : r.lines) {
        const bool contains = key.compare(0, path.size(), path) == 0 &&
                              (key.size() == path.size() || key[path.size()] == '.' || key[path.size()] == '[');
        if (contains && path.size() >= best) {
          best = path.size();
          line = l;
        }
      }
      return ErrorContext{r.file, line, key};
    }
  }
  return std::nullopt;
}

std::optional<ErrorContext> SourceMap::place(const std::string& field) const {
  // Rules by decreasing prefix length: the most specific place wins.
  std::vector<const Rule*> order;
  for (const Rule& r : rules_)
    if (field.empty() ? r.prefix.empty() && r.kind == Kind::Document : continues(field, r.prefix)) order.push_back(&r);
  std::stable_sort(order.begin(), order.end(),
                   [](const Rule* a, const Rule* b) { return a->prefix.size() > b->prefix.size(); });
  for (const Rule* r : order)
    if (auto where = resolve(*r, field)) return where;
  return std::nullopt;
}

void SourceMap::locate(Error& e) const {
  if (!e.context().file.empty()) return;
  if (auto where = place(e.context().field)) {
    // A place without a line keeps a line the error had (a reader's own row count).
    if (!where->line && e.context().line) where->line = e.context().line;
    e.relocate(std::move(*where));
  }
}

}  // namespace meridian::io
