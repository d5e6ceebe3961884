#!/usr/bin/env bash
# The real-music data for tests/bench/beats/score.py: every usable demo song that Debian's
# hydrogen and lmms packages ship, rendered with the package's own command-line renderer to
# DIR/NAME.wav, and its truth read from the project file (scripts/beats-truth.py) into
# DIR/NAME.truth (TIME<TAB>POS a line, 1 = downbeat) and DIR/NAME.json (bpm, meter, project,
# licence); and the rock and metal band recordings of Debian's fretsonfire-songs-muldjord and
# -sectoid packages, linked as DIR/fof-NAME.ogg with their truth from the note charts their
# makers wrote for them (scripts/beats-truth-charts.py). The truth is the composers' grid, not
# anything seqc computed.
#
#   scripts/beats-data.sh [DIR]        DIR defaults to build/beats-data in the source tree
#
# Songs already rendered are kept (delete DIR/NAME.wav to render one again). A render that fails
# or takes longer than BEATS_RENDER_TIMEOUT seconds (default 600) is logged in DIR/render.log and
# skipped; the others go on. Run as root, it installs the missing packages with apt-get; otherwise
# it says what to install and exits 1.
set -u
root=$(cd "$(dirname "$0")/.." && pwd) || exit 1
dir=${1:-$root/build/beats-data}
timeout_s=${BEATS_RENDER_TIMEOUT:-600}
packages=(hydrogen lmms python3-mir-eval fretsonfire-songs-muldjord fretsonfire-songs-sectoid)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  if [[ $(id -u) == 0 ]]; then
    echo "beats-data: installing ${missing[*]}"
    apt-get update && DEBIAN_FRONTEND=noninteractive apt-get install -y "${missing[@]}" || exit 1
  else
    echo "beats-data: missing packages: ${missing[*]}" >&2
    echo "  install them with: sudo apt-get install -y ${missing[*]}" >&2
    exit 1
  fi
fi

mkdir -p "$dir" || exit 1
log=$dir/render.log
truth=$root/scripts/beats-truth.py
# Debian's Python, as the tests use (the truth writer needs only its standard library).
python=/usr/bin/python3
[[ -x $python ]] || python=python3

# LMMS refuses to start as root without --allowroot, and needs no display with offscreen Qt.
lmms_root=()
[[ $(id -u) == 0 ]] && lmms_root=(--allowroot)
export QT_QPA_PLATFORM=offscreen

declare -A seconds=([hydrogen]=0 [lmms]=0)
declare -A rendered=([hydrogen]=0 [lmms]=0)
failed=0
if ! list=$("$python" "$truth" list 2>"$dir/excluded.log"); then
  echo "beats-data: $truth list failed" >&2
  exit 1
fi
sed 's/^/beats-data: /' "$dir/excluded.log"
while IFS=$'\t' read -r name kind project; do
  out=$dir/$name.wav
  [[ -s $out ]] && continue
  tmp=$dir/$name.part.wav
  rm -f "$tmp"
  start=$(date +%s.%N)
  if [[ $kind == hydrogen ]]; then
    # h2cli may try JACK and ALSA first; it still renders to the file (its chatter goes to the log).
    timeout -s KILL "$timeout_s" h2cli -s "$project" -o "$tmp" </dev/null >>"$log" 2>&1
  else
    timeout -s KILL "$timeout_s" lmms "${lmms_root[@]}" render "$project" -o "$tmp" -f wav \
      </dev/null >>"$log" 2>&1
  fi
  status=$?
  took=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
  if [[ $status == 0 && -s $tmp ]]; then
    mv "$tmp" "$out"
    seconds[$kind]=$(awk -v a="${seconds[$kind]}" -v b="$took" 'BEGIN { print a + b }')
    rendered[$kind]=$((rendered[$kind] + 1))
    printf 'beats-data: %s rendered in %.1f s\n' "$name" "$took"
  else
    rm -f "$tmp"
    failed=$((failed + 1))
    reason="exit status $status"
    [[ $status == 137 ]] && reason="no result within ${timeout_s} s"
    echo "beats-data: FAILED $name ($kind, $project): $reason" | tee -a "$log" >&2
  fi
done <<<"$list"

for kind in hydrogen lmms; do
  printf 'beats-data: %s: %d songs rendered in %.0f s\n' "$kind" "${rendered[$kind]}" \
    "${seconds[$kind]}"
done
"$python" "$truth" write "$dir" || { echo "beats-data: $truth write failed" >&2; exit 1; }
# The band recordings need no render: their truth comes from the charts their makers wrote.
"$python" "$root/scripts/beats-truth-charts.py" "$dir" | sed 's/^/beats-data: /' ||
  { echo "beats-data: beats-truth-charts.py failed" >&2; exit 1; }
truths=("$dir"/*.truth)
[[ -e ${truths[0]} ]] || truths=()
echo "beats-data: ${#truths[@]} songs with truth in $dir" \
  "($failed renders failed; excluded projects in $dir/excluded.txt)"
