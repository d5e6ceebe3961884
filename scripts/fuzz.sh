#!/usr/bin/env bash
# Builds every libFuzzer target with clang (ASan + UBSan, SEQC_FUZZ=ON, in build-fuzz/) and runs
# each for SECONDS (default 60), one after the other, printing its final statistics
# (executions, coverage). New inputs go to build-fuzz/corpus/<target>/ (the repository's
# corpus/<target>/ and the seeds are read, not written); a crash is saved in build-fuzz/crashes/
# and fails the script. Copy an input worth keeping, e.g. a fixed crash, into
# tests/fuzz/corpus/<target>/ so CI replays it.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-60}
shift || true
targets=("$@")
if ((${#targets[@]} == 0)); then
  targets=(check yaml views d6a lsc_stream lsc_hid raspblock)
fi
build=${SEQC_FUZZ_BUILD_DIR:-$root/build-fuzz}
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DSEQC_FUZZ=ON \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" --target "${targets[@]/#/fuzz_}"
mkdir -p "$build/crashes"
status=0
for t in "${targets[@]}"; do
  mkdir -p "$build/corpus/$t"
  seeds=("$root/tests/fuzz/corpus/$t")
  args=()
  case $t in
    check | yaml | views)
      seeds+=("$root/examples" "$root/tests/golden" "$root/tests/compiler/hostile")
      # Fitting a waltz-sized file takes seconds under ASan + UBSan + coverage (0.05 s in a
      # release build): a 10 s limit reported valid examples as hangs.
      args+=(-dict="$root/tests/fuzz/yaml.dict" -max_len=4096 -timeout=60)
      ;;
  esac
  echo "== $t: ${seconds} s"
  # args last: a target's own -timeout replaces the default.
  if ! "$build/tests/fuzz/fuzz_$t" "$build/corpus/$t" "${seeds[@]}" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 "${args[@]}" -print_final_stats=1 \
    -artifact_prefix="$build/crashes/$t-" 2>"$build/$t.log"; then
    echo "fuzz_$t FAILED; see $build/$t.log and $build/crashes/" >&2
    status=1
  fi
  grep -E "^#[0-9]+ *DONE|stat::number_of_executed_units|stat::peak_rss_mb" "$build/$t.log" || true
done
exit $status
