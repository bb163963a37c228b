#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "meridian/core/error.hpp"
#include "meridian/io/document.hpp"
#include "input_limits.hpp"

// Node's parser for YAML and JSON files: yaml-cpp, its tree copied into a DocumentTree.
namespace meridian::io {
namespace {

// Whether line `line` (1-based) of a YAML block document has a tab in its
// leading whitespace. A JSON document (a flow mapping) may indent with tabs.
bool indented_with_tab(const std::string& text, int line) {
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && text[first] == '{') return false;
  std::size_t b = 0;
  for (int l = 1; l < line; ++l) {
    b = text.find('\n', b);
    if (b == std::string::npos) return false;
    ++b;
  }
  for (std::size_t i = b; i < text.size() && (text[i] == ' ' || text[i] == '\t'); ++i)
    if (text[i] == '\t') return true;
  return false;
}

// Nesting and size limits of a document: anchors and aliases can make a small file a huge (or,
// through a self-reference, endless) tree once copied out of yaml-cpp.
constexpr std::size_t kMaxNodes = 5'000'000;

struct Copier {
  const std::string& file;
  std::size_t nodes = 0;

  DocumentTree copy(const YAML::Node& n, int depth) {
    if (depth > kMaxDocumentDepth)
      throw ParseError(fmt::format("the document is nested more than {} levels deep", kMaxDocumentDepth),
                       {file, line_of(n), {}});
    if (++nodes > kMaxNodes)
      throw ParseError(fmt::format("the document has more than {} nodes (aliases expanded)", kMaxNodes),
                       {file, line_of(n), {}});
    DocumentTree t;
    t.line = n.Mark().line >= 0 ? n.Mark().line + 1 : 0;
    switch (n.Type()) {
      case YAML::NodeType::Scalar:
        t.kind = DocumentTree::Kind::Scalar;
        t.scalar = n.Scalar();
        break;
      case YAML::NodeType::Sequence:
        t.kind = DocumentTree::Kind::Sequence;
        for (const auto& c : n) t.elements.push_back(copy(c, depth + 1));
        break;
      case YAML::NodeType::Map:
        t.kind = DocumentTree::Kind::Map;
        for (const auto& kv : n) {
          DocumentTree::Member m;
          m.key = kv.first.IsScalar() ? kv.first.Scalar() : std::string();
          m.key_line = kv.first.Mark().line >= 0 ? kv.first.Mark().line + 1 : 0;
          m.value = copy(kv.second, depth + 1);
          t.members.push_back(std::move(m));
        }
        break;
      default:
        t.kind = DocumentTree::Kind::Null;
    }
    return t;
  }

  static std::optional<int> line_of(const YAML::Node& n) {
    return n.Mark().line >= 0 ? std::optional<int>(n.Mark().line + 1) : std::nullopt;
  }
};

}  // namespace

Node Node::load_file(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw IoError("is a directory, not a file", {file, std::nullopt, {}});
  detail::check_readable_path(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot open the file", {file, std::nullopt, {}});
  std::stringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw IoError("cannot read the file", {file, std::nullopt, {}});
  return load_text(ss.str(), file);
}

Node Node::load_text(const std::string& text, const std::string& file_name) {
  auto file = std::make_shared<const std::string>(file_name);
  if (text.find_first_not_of(" \t\r\n") == std::string::npos)
    throw ParseError("the file is empty", {*file, std::nullopt, {}});
  if (text.find('\0') != std::string::npos)
    throw ParseError("the file contains NUL bytes: not a text file", {*file, std::nullopt, {}});
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    const std::optional<int> line =
        e.mark.line >= 0 ? std::optional<int>(e.mark.line + 1) : std::nullopt;
    if (line && indented_with_tab(text, *line))
      throw ParseError(
          fmt::format("tabs are not allowed for indentation (line {}); indent with spaces", *line),
          {*file, line, {}});
    throw ParseError(fmt::format("syntax error: {} (column {})", e.msg, e.mark.column + 1),
                     {*file, line, {}});
  }
  Copier copier{*file};
  auto tree = std::make_shared<const DocumentTree>(copier.copy(root, 0));
  Node n(tree, tree.get(), "", file, std::make_shared<LineMap>());
  if (!n.is_map()) n.fail("the top level must be a mapping of fields (YAML) or an object (JSON)");
  return n;
}

}  // namespace meridian::io
