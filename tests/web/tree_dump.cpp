// Prints the document tree of a YAML/JSON file as yaml-cpp parses it (Node::load_file), as tree
// JSON: the reference the field book's JavaScript parser is compared with (compare_yaml_trees.mjs).
#include <cstdio>
#include <exception>

#include "meridian/io/document.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: tree_dump FILE.yaml\n");
    return 2;
  }
  try {
    const meridian::io::Node root = meridian::io::Node::load_file(argv[1]);
    std::printf("%s\n", meridian::io::to_tree_json(root.tree()).c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
