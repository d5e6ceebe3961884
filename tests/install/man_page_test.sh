#!/usr/bin/env bash
# The man page is generated from the command line; this checks the result: groff formats it
# without a warning, and every subcommand and every option `seqc SUBCOMMAND --help` lists
# appears in it.
# Usage: man_page_test.sh SEQC_BINARY SEQC_1
set -uo pipefail
seqc=$1
page=$2
fail=0
warnings=$(groff -man -ww -z "$page" 2>&1)
if [ -n "$warnings" ]; then
  echo "FAIL: groff warns: $warnings" >&2
  fail=1
fi
# The page as text, hyphens unescaped, so it can be compared with --help.
text=$(sed 's/\\-/-/g; s/\\f[BIR]//g' "$page")
commands=$("$seqc" --help | awk '/^Subcommands:/ {on=1; next} on && /^  [a-z]/ {print $1}')
[ -n "$commands" ] || { echo "FAIL: no subcommands in --help" >&2; exit 1; }
for c in $commands; do
  subs=$("$seqc" "$c" --help | awk '/^Subcommands:/ {on=1; next} on && /^  [a-z]/ {print $1}')
  for path in "$c" $(for s in $subs; do echo "$c/$s"; done); do
    words=${path/\// }
    # shellcheck disable=SC2086
    help=$("$seqc" $words --help)
    grep -qF "seqc $words" <<<"$text" || { echo "FAIL: 'seqc $words' not in the page" >&2; fail=1; }
    for opt in $(grep -oE '(^|[ ,])--[a-z][a-z-]*' <<<"$help" | tr -d ' ,' | sort -u); do
      [ "$opt" = "--help" ] && continue
      grep -qF -- "$opt" <<<"$text" || { echo "FAIL: $opt of 'seqc $words' missing" >&2; fail=1; }
    done
  done
done
[ "$fail" -eq 0 ] && echo "man page: formats cleanly and documents every subcommand and option"
exit "$fail"
