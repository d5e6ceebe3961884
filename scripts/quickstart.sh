#!/usr/bin/env bash
# Installs what is missing, builds, installs seqc into /usr/local (bin, man page, completions,
# schema, examples, udev rule) and uploads examples/walk.yaml to the built-in emulator with the
# installed `seqc`, which is then on PATH. SEQC_PREFIX picks another prefix.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
# The tool and what `cmake --install` copies (its man page and completions) only: the tests,
# GoogleTest's and the benchmarks are the test command's (scripts/test.sh) to build.
SEQC_BUILD_TARGETS="seqc seqc-docs" "$root/scripts/build.sh"
build=${SEQC_BUILD_DIR:-$root/build}
prefix=${SEQC_PREFIX:-/usr/local}
sudo=""
if [ ! -w "$prefix" ] && [ "$(id -u)" -ne 0 ]; then
  sudo="sudo"
fi
$sudo cmake --install "$build" --prefix "$prefix" >/dev/null
echo "seqc: installed $("$prefix/bin/seqc" --version) into $prefix" >&2
if ! command -v seqc >/dev/null 2>&1; then
  echo "seqc: $prefix/bin is not on PATH; add it: export PATH=\"$prefix/bin:\$PATH\"" >&2
fi
PATH="$prefix/bin:$PATH" seqc upload "$root/examples/walk.yaml" --port emu:xarm --run
