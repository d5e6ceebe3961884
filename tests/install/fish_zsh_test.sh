#!/usr/bin/env bash
# The generated fish completion answered by fish itself (`complete -C`, what fish runs on Tab),
# and the zsh one parsed by zsh (-n). Usage: fish_zsh_test.sh SEQC_FISH _SEQC
set -uo pipefail
fish_file=$1
zsh_file=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
touch "$work/walk.yaml" "$work/notes.txt"
fail=0
zsh -n "$zsh_file" || { echo "FAIL: zsh cannot parse $zsh_file" >&2; fail=1; }
grep -q '^#compdef seqc' "$zsh_file" || { echo "FAIL: no #compdef line" >&2; fail=1; }

# complete LINE -> the candidates fish offers (first column), sorted, space-separated.
complete_line() {
  (cd "$work" && fish -c "source '$fish_file'; complete -C '$1'") | cut -f1 | sort | tr '\n' ' ' |
    sed 's/ $//'
}
expect() {
  local got
  got=$(complete_line "$2")
  [ "$got" = "$1" ] || { echo "FAIL: fish '$2': want '$1', got '$got'" >&2; fail=1; }
}
expect "calibrate check compile" "seqc c"
expect "--strict" "seqc check --st"
expect "json sarif text" "seqc check --format "
expect "erase" "seqc group e"
expect "walk.yaml" "seqc check w"
expect "--forever" "seqc upload --fore"
[ "$fail" -eq 0 ] && echo "fish completion answers; zsh completion parses"
exit "$fail"
