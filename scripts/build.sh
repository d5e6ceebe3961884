#!/usr/bin/env bash
# Configures and builds seqc into build/ (or $SEQC_BUILD_DIR). Extra arguments go to cmake.
# SEQC_BUILD_TARGETS (space-separated) builds only those targets; by default everything.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${SEQC_BUILD_DIR:-$root/build}
cmake -S "$root" -B "$build" -G Ninja "$@" >/dev/null
targets=()
for t in ${SEQC_BUILD_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build "$build" "${targets[@]}"
