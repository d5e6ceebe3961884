#!/usr/bin/env bash
# The generated bash completion, driven the way bash drives it: COMP_WORDS/COMP_CWORD set, the
# function called, COMPREPLY read. `seqc` on PATH is a stand-in that lists one port, so --port
# completion is checked without hardware.
# Usage: completion_test.sh GENERATED_SEQC_BASH
set -uo pipefail
completion=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/bin" "$work/files/walks"
cat >"$work/bin/seqc" <<'STUB'
#!/bin/sh
[ "$1 $2" = "ports --names" ] && echo /dev/ttyUSB7
STUB
chmod +x "$work/bin/seqc"
touch "$work/files/walk.yaml" "$work/files/wave.yml" "$work/files/notes.txt" "$work/files/w.hex"
export PATH="$work/bin:$PATH"
cd "$work/files" || exit 1
# shellcheck disable=SC1090
source "$completion"

failures=0
# complete WORDS... -> the sorted COMPREPLY, space-separated; the last word is the one completed.
complete_words() {
  COMP_WORDS=("$@")
  COMP_CWORD=$((${#COMP_WORDS[@]} - 1))
  COMPREPLY=()
  _seqc
  printf '%s\n' "${COMPREPLY[@]}" | sort | tr '\n' ' ' | sed 's/ $//'
}
expect() {
  local want=$1
  shift
  local got
  got=$(complete_words "$@")
  if [ "$got" != "$want" ]; then
    echo "FAIL: seqc ${*:2}: want '$want', got '$got'" >&2
    failures=$((failures + 1))
  fi
}

expect "calibrate check compile" seqc c
expect "upload" seqc up
expect "bus-info" seqc bus
expect "erase" seqc group e
expect "run" seqc group r
expect "--strict" seqc check --st
expect "--format" seqc check --fo
expect "json sarif text" seqc check --format ""
expect "always" seqc --color al
expect "--port" seqc upload --po
expect "/dev/ttyUSB7 emu:raspblock emu:xarm hid" seqc upload --port ""
expect "emu:raspblock emu:xarm" seqc play x.yaml --port emu
# Choreography files by extension, and folders to walk into.
expect "walk.yaml walks wave.yml" seqc check w
expect "walk.yaml walks wave.yml" seqc upload --port emu:xarm w
# A command taking any file: everything.
expect "w.hex walk.yaml walks wave.yml" seqc decode w
# An option taking a file completes files; one taking a number offers nothing.
expect "notes.txt" seqc compile walk.yaml -o no
expect "" seqc upload --group ""
# Global options fall through to every subcommand.
expect "--quiet" seqc upload --qu
# Past a value, the subcommand is still found: `--port X` is skipped.
expect "--run" seqc upload --port emu:xarm walk.yaml --ru

if [ "$failures" -ne 0 ]; then
  echo "$failures completion(s) wrong" >&2
  exit 1
fi
echo "bash completion: all cases passed"
