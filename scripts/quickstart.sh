#!/usr/bin/env bash
# Installs what is missing, builds, and uploads examples/walk.yaml to the built-in emulator.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
"${SEQC_BUILD_DIR:-$root/build}/runtime/cli/seqc" upload "$root/examples/walk.yaml" --port emu:xarm --run
