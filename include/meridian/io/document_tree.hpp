#pragma once
/// \file document_tree.hpp
/// A parsed YAML or JSON document as a plain tree — what io::Node reads. The
/// tree is built by a parser: yaml-cpp for files (Node::load_file), or any
/// other that writes the tree JSON below (Node::load_tree_json: the browser
/// field book's YAML parser). The readers above io::Node see no parser, so
/// the same rules and messages hold whichever built the tree.
///
/// Scalars keep their text as written ("0.100" stays "0.100": readers take
/// booked digits from it); lines are 1-based, 0 where the parser did not say.

#include <string>
#include <utility>
#include <vector>

namespace meridian::io {

/// Deepest nesting a document may have (either parser): deeper is a ParseError, not a stack overflow.
inline constexpr int kMaxDocumentDepth = 200;
/// The largest magnitude io::Node::number() accepts, in the field's own unit (1e30: a larger
/// value is a slip; a sigma of 1e200 overflowed when squared).
inline constexpr double kMaxDocumentNumber = 1e30;

struct DocumentTree {
  enum class Kind { Null, Scalar, Sequence, Map };
  /// One member of a map: its key, the key's own line, and the value.
  struct Member;
  Kind kind = Kind::Null;
  std::string scalar;            ///< Scalar: the text as written (without quotes)
  int line = 0;                  ///< 1-based line of the node (0: unknown)
  std::vector<DocumentTree> elements;  ///< Sequence
  std::vector<Member> members;   ///< Map, in the order written (duplicates kept: allow_only names them)
};

struct DocumentTree::Member {
  std::string key;
  int key_line = 0;
  DocumentTree value;
};

/// `tree` as the tree JSON that Node::load_tree_json reads (document.hpp), compact, one line.
std::string to_tree_json(const DocumentTree& tree);

}  // namespace meridian::io
