// The field book's YAML parser: a YAML (or JSON) text to the document tree that Meridian's readers
// take (include/meridian/io/document.hpp, Node::load_tree_json): every node's kind, its 1-based
// line, scalars as written (a plain "0.100" stays "0.100"), map members with their keys' lines.
// The parser is the npm package `yaml` (web/package.json); the CLI parses with yaml-cpp, and the
// test tests/web/yaml_tree.test compares the two trees on every book.
import { parseDocument, isMap, isSeq, isScalar, isAlias, isPair, LineCounter } from "yaml";

export class YamlSyntaxError extends Error {
  constructor(message, line) {
    super(message);
    this.line = line;
  }
}

// Parse `text`; throws YamlSyntaxError(message, line) for a syntax error.
export function yamlTree(text) {
  const lines = new LineCounter();
  const doc = parseDocument(text, { lineCounter: lines, keepSourceTokens: true, uniqueKeys: false, version: "1.2" });
  if (doc.errors.length) {
    const e = doc.errors[0];
    const line = e.linePos && e.linePos[0] ? e.linePos[0].line : 0;
    throw new YamlSyntaxError(e.message.split("\n")[0], line);
  }
  const lineOf = (offset) => (offset === undefined || offset === null ? 0 : lines.linePos(offset).line);
  const depthLimit = 200;
  const walk = (node, depth) => {
    if (depth > depthLimit) throw new YamlSyntaxError(`the document is nested more than ${depthLimit} levels deep`, 0);
    if (isAlias(node)) node = node.resolve(doc);
    if (node === null || node === undefined) return { kind: "null", line: 0 };
    let start = node.range ? node.range[0] : undefined;
    // yaml-cpp marks a node with an anchor at its "&name" (the node's properties), `yaml` at its content.
    if (node.anchor && start !== undefined) {
      const at = text.lastIndexOf("&" + node.anchor, start);
      if (at >= 0) start = at;
    }
    const line = start !== undefined ? lineOf(start) : 0;
    if (isScalar(node)) {
      if (node.value === null) return { kind: "null", line };
      const plain = node.type === "PLAIN" && node.srcToken && typeof node.srcToken.source === "string";
      return { kind: "scalar", line, scalar: plain ? node.srcToken.source : String(node.value) };
    }
    if (isSeq(node)) return { kind: "sequence", line, elements: node.items.map((c) => walk(c, depth + 1)) };
    if (isMap(node)) {
      const members = node.items.map((p) => {
        const key = isScalar(p.key) ? String(p.key.value) : "";
        const keyLine = p.key && p.key.range ? lineOf(p.key.range[0]) : 0;
        return { key, key_line: keyLine, value: walk(p.value, depth + 1) };
      });
      return { kind: "map", line, members };
    }
    return { kind: "null", line };
  };
  return walk(doc.contents, 0);
}
