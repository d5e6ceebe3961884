#!/usr/bin/env bash
# Makes the README's picture of `seqc preview` (docs/images/preview.png): the preview of
# examples/pick-and-place.yaml at 2.6 s, as headless Chromium shows it in a 1140 x 860 window.
# Usage: scripts/preview-screenshot.sh [SEQC]   (default: build/runtime/cli/seqc)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seqc=${1:-$root/build/runtime/cli/seqc}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$seqc" preview "$root/examples/pick-and-place.yaml" -o "$tmp/preview.html"
chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --user-data-dir="$tmp/profile" \
  --window-size=1140,860 --screenshot="$root/docs/images/preview.png" \
  "file://$tmp/preview.html#t=2.6" 2>/dev/null
echo "docs/images/preview.png"
