#!/usr/bin/env bash
# `cmake --install` into a scratch prefix puts every file where the README says, and the
# installed binary runs on an installed example.
# Usage: install_test.sh BUILD_DIR
set -euo pipefail
prefix=$(mktemp -d)
trap 'rm -rf "$prefix"' EXIT
cmake --install "$1" --prefix "$prefix" >/dev/null
for f in bin/seqc share/seqc/seqc.schema.json share/man/man1/seqc.1.gz \
  share/bash-completion/completions/seqc share/zsh/site-functions/_seqc \
  share/fish/vendor_completions.d/seqc.fish lib/udev/rules.d/70-seqc.rules \
  share/doc/seqc/examples/walk.yaml share/doc/seqc/examples/car-dance.yaml \
  share/doc/seqc/copyright share/doc/seqc/CHANGELOG.md share/doc/seqc/schemas/seqc.schema.json; do
  [ -e "$prefix/$f" ] || { echo "FAIL: $f not installed" >&2; exit 1; }
done
# Outside /usr, zsh reads only site-functions (Debian 12's fpath), never vendor-completions.
[ ! -e "$prefix/share/zsh/vendor-completions/_seqc" ] ||
  { echo "FAIL: _seqc installed where zsh does not look under $prefix" >&2; exit 1; }
PATH="$prefix/bin:$PATH" seqc check "$prefix/share/doc/seqc/examples/car-dance.yaml"
echo "cmake --install: every file in place"
