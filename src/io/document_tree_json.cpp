#include <memory>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "meridian/core/error.hpp"
#include "meridian/io/document.hpp"

// Node's reader of a tree another parser made (document.hpp, load_tree_json): the browser field
// book parses YAML in JavaScript and hands Meridian's readers the tree, lines and text as written.
namespace meridian::io {
namespace {


struct TreeReader {
  const std::string& file;

  [[noreturn]] void bad(const std::string& what, int line) const {
    throw ParseError("not a document tree: " + what, {file, line > 0 ? std::optional<int>(line) : std::nullopt, {}});
  }

  static int line_of(const nlohmann::json& j, const char* key) {
    const auto it = j.find(key);
    if (it == j.end()) return 0;
    if (!it->is_number_integer() || it->get<long long>() < 0 || it->get<long long>() > 100'000'000) return -1;
    return static_cast<int>(it->get<long long>());
  }

  DocumentTree read(const nlohmann::json& j, int depth) const {
    if (depth > kMaxDocumentDepth) bad(fmt::format("nested more than {} levels deep", kMaxDocumentDepth), 0);
    if (!j.is_object()) bad("a node is not an object", 0);
    DocumentTree t;
    t.line = line_of(j, "line");
    if (t.line < 0) bad("\"line\" must be a whole number >= 0", 0);
    const auto kind = j.find("kind");
    if (kind == j.end() || !kind->is_string()) bad("a node without \"kind\"", t.line);
    const std::string k = kind->get<std::string>();
    if (k == "null") {
      t.kind = DocumentTree::Kind::Null;
    } else if (k == "scalar") {
      t.kind = DocumentTree::Kind::Scalar;
      const auto s = j.find("scalar");
      if (s == j.end() || !s->is_string()) bad("a scalar without its text (\"scalar\")", t.line);
      t.scalar = s->get<std::string>();
    } else if (k == "sequence") {
      t.kind = DocumentTree::Kind::Sequence;
      const auto e = j.find("elements");
      if (e == j.end() || !e->is_array()) bad("a sequence without \"elements\"", t.line);
      for (const auto& c : *e) t.elements.push_back(read(c, depth + 1));
    } else if (k == "map") {
      t.kind = DocumentTree::Kind::Map;
      const auto m = j.find("members");
      if (m == j.end() || !m->is_array()) bad("a map without \"members\"", t.line);
      for (const auto& c : *m) {
        if (!c.is_object() || !c.contains("key") || !c["key"].is_string() || !c.contains("value"))
          bad("a map member is not {\"key\": text, \"key_line\": N, \"value\": node}", t.line);
        DocumentTree::Member member;
        member.key = c["key"].get<std::string>();
        member.key_line = line_of(c, "key_line");
        if (member.key_line < 0) bad("\"key_line\" must be a whole number >= 0", t.line);
        member.value = read(c["value"], depth + 1);
        t.members.push_back(std::move(member));
      }
    } else {
      bad(fmt::format("unknown kind \"{}\" (null, scalar, sequence or map)", k), t.line);
    }
    return t;
  }
};

nlohmann::json to_json(const DocumentTree& t) {
  nlohmann::json j;
  switch (t.kind) {
    case DocumentTree::Kind::Null:
      j["kind"] = "null";
      break;
    case DocumentTree::Kind::Scalar:
      j["kind"] = "scalar";
      j["scalar"] = t.scalar;
      break;
    case DocumentTree::Kind::Sequence:
      j["kind"] = "sequence";
      j["elements"] = nlohmann::json::array();
      for (const auto& e : t.elements) j["elements"].push_back(to_json(e));
      break;
    case DocumentTree::Kind::Map:
      j["kind"] = "map";
      j["members"] = nlohmann::json::array();
      for (const auto& m : t.members)
        j["members"].push_back({{"key", m.key}, {"key_line", m.key_line}, {"value", to_json(m.value)}});
      break;
  }
  j["line"] = t.line;
  return j;
}

}  // namespace

std::string to_tree_json(const DocumentTree& tree) {
  // Scalars were checked as UTF-8 by nobody yet: replace what is not, rather than throw here.
  return to_json(tree).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

Node Node::load_tree_json(const std::string& tree_json, const std::string& file_name) {
  auto file = std::make_shared<const std::string>(file_name);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(tree_json);
  } catch (const nlohmann::json::exception& e) {
    throw ParseError(fmt::format("not a document tree: {}", e.what()), {*file, std::nullopt, {}});
  }
  auto tree = std::make_shared<const DocumentTree>(TreeReader{*file}.read(j, 0));
  Node n(tree, tree.get(), "", file, std::make_shared<LineMap>());
  if (!n.is_map()) n.fail("the top level must be a mapping of fields (YAML) or an object (JSON)");
  return n;
}

}  // namespace meridian::io
