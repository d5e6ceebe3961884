#!/usr/bin/env bash
# Mutation testing: applies each single-line mutation of scripts/mutants/catalogue.txt to a
# scratch copy of the working tree, rebuilds, runs the tests that should catch it, and prints
# killed / survived / no longer applies. Not part of CI (it takes tens of minutes); run it
# before resolving work that touches protocol, compiler, fitting, uploader, emulator or CLI.
#
#   scripts/mutants.sh                 every mutation
#   scripts/mutants.sh back-in-out     only the mutations whose id contains one of the words
#   scripts/mutants.sh --list          the catalogue, without running anything
#
# The scratch copy lives in $SEQC_MUTANTS_DIR (default /tmp/seqc-mutants) and keeps its build
# between runs, so a second run only rebuilds what the mutations touch. Exit status: 0 when no
# mutation survived, 1 otherwise, 2 on a usage or set-up error.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
exec python3 "$root/scripts/mutants/run.py" --root "$root" "$@"
