#!/usr/bin/env bash
# The pre-commit hook as a choreography repository uses it: a scratch git repository with a
# good and a bad file, `pre-commit try-repo` pointed at this repository's hook definition, and
# the built seqc first on PATH. The hook must fail on the bad file, naming it with line and
# column, and pass once the file is fixed.
# Usage: precommit_test.sh SOURCE_DIR SEQC_BINARY
set -uo pipefail
src=$1
bin_dir=$(cd "$(dirname "$2")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export PATH="$bin_dir:$PATH" HOME="$work/home" PRE_COMMIT_HOME="$work/cache"
export GIT_AUTHOR_NAME=t GIT_AUTHOR_EMAIL=t@example.invalid GIT_COMMITTER_NAME=t \
  GIT_COMMITTER_EMAIL=t@example.invalid
mkdir -p "$work/home" "$work/choreo"
# try-repo reads the hook from a git repository: a copy of the definition, committed.
mkdir "$work/hooks"
cp "$src/.pre-commit-hooks.yaml" "$work/hooks/"
git -C "$work/hooks" init -q && git -C "$work/hooks" add . && git -C "$work/hooks" commit -qm hooks
cd "$work/choreo" && git init -q
cp "$src/tests/data/walk-joints.yaml" good.yaml
printf 'robot: xarm\nsequence:\n  - move: home\n    tme: 1s\n' >bad.yaml
git add .
out=$(pre-commit try-repo "$work/hooks" seqc-check --all-files 2>&1)
status=$?
if [ "$status" -eq 0 ]; then
  echo "FAIL: the hook passed a bad file:" >&2
  echo "$out" >&2
  exit 1
fi
grep -q "bad.yaml:4:5: error: unknown key 'tme'" <<<"$out" ||
  { echo "FAIL: no located diagnostic in:" >&2; echo "$out" >&2; exit 1; }
printf 'robot: xarm\nsequence:\n  - move: home\n    time: 1s\n' >bad.yaml
git add .
out=$(pre-commit try-repo "$work/hooks" seqc-check --all-files 2>&1) ||
  { echo "FAIL: the hook failed on good files:" >&2; echo "$out" >&2; exit 1; }
echo "pre-commit hook: fails on the bad file with its location, passes once fixed"
