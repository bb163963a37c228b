// The field book's YAML parser (web/fieldbook/yaml-tree.mjs, npm `yaml`) against the CLI's
// (yaml-cpp, through tests/web/tree_dump): on every book given, the same tree — kinds, scalars as
// written, keys, and the lines Meridian's messages name. Exits 1 on the first book that differs.
// Usage: node compare_yaml_trees.mjs TREE_DUMP BOOK.yaml...
import { readFileSync } from "node:fs";
import { execFileSync } from "node:child_process";
import { yamlTree } from "../../web/fieldbook/yaml-tree.mjs";

const [dump, ...books] = process.argv.slice(2);
if (!dump || books.length === 0) {
  console.error("usage: node compare_yaml_trees.mjs TREE_DUMP BOOK.yaml...");
  process.exit(2);
}

// The first difference of two trees, as a path and both values; null when equal.
function difference(a, b, path) {
  if (a.kind !== b.kind) return `${path}: kind ${a.kind} (yaml-cpp) vs ${b.kind} (yaml)`;
  if (a.kind !== "null" && a.line !== b.line) return `${path}: line ${a.line} (yaml-cpp) vs ${b.line} (yaml)`;
  if (a.kind === "scalar" && a.scalar !== b.scalar)
    return `${path}: ${JSON.stringify(a.scalar)} (yaml-cpp) vs ${JSON.stringify(b.scalar)} (yaml)`;
  if (a.kind === "sequence") {
    if (a.elements.length !== b.elements.length) return `${path}: ${a.elements.length} vs ${b.elements.length} elements`;
    for (let i = 0; i < a.elements.length; ++i) {
      const d = difference(a.elements[i], b.elements[i], `${path}[${i}]`);
      if (d) return d;
    }
  }
  if (a.kind === "map") {
    if (a.members.length !== b.members.length) return `${path}: ${a.members.length} vs ${b.members.length} members`;
    for (let i = 0; i < a.members.length; ++i) {
      const [x, y] = [a.members[i], b.members[i]];
      const p = path ? `${path}.${x.key}` : x.key;
      if (x.key !== y.key) return `${p}: key ${JSON.stringify(x.key)} vs ${JSON.stringify(y.key)}`;
      if (x.key_line !== y.key_line) return `${p}: key line ${x.key_line} vs ${y.key_line}`;
      const d = difference(x.value, y.value, p);
      if (d) return d;
    }
  }
  return null;
}

let failed = 0, nodes = 0;
const count = (t) => 1 + (t.elements || []).reduce((s, e) => s + count(e), 0) + (t.members || []).reduce((s, m) => s + count(m.value), 0);
for (const book of books) {
  const native = JSON.parse(execFileSync(dump, [book], { encoding: "utf8", maxBuffer: 1 << 28 }));
  const js = yamlTree(readFileSync(book, "utf8"));
  const d = difference(native, js, "");
  nodes += count(native);
  if (d) {
    ++failed;
    console.log(`FAIL ${book}: ${d}`);
  } else {
    console.log(`ok   ${book}`);
  }
}
console.log(`${books.length - failed} of ${books.length} books give the same tree (${nodes} nodes)`);
process.exit(failed ? 1 : 0);
