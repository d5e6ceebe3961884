#!/usr/bin/env bash
# Runs a command with a PulseAudio server it can reach: the one already running (PULSE_SERVER or
# the user's socket), else a private server with a null sink (44.1 kHz) on a socket in a
# temporary folder, exported as PULSE_SERVER and stopped afterwards. CI runs as root with no
# session, so the private server is started with --system=false (it warns that it runs as
# root). Exit status 77 (a skipped test) when PulseAudio is not installed.
#
# Where real-time scheduling is allowed (root, or an RLIMIT_RTPRIO allowance), the private server
# and the command run under SCHED_FIFO: what the tests measure is seqc's timing, and on a loaded
# machine the server's main thread and the tests' own recorders at normal priority were late by
# up to a second now and then, which no bound in milliseconds survives.
set -euo pipefail
fifo=()
if command -v chrt >/dev/null && chrt -f 5 true 2>/dev/null; then
  fifo=(chrt -f 5)
fi
if ! command -v pactl >/dev/null || ! command -v pulseaudio >/dev/null; then
  echo "with_pulse: pulseaudio and pactl are needed (scripts/install-deps.sh)" >&2
  exit 77
fi
if pactl info >/dev/null 2>&1; then
  exec "${fifo[@]}" "$@"
fi
dir=$(mktemp -d)
export XDG_RUNTIME_DIR="$dir" HOME="$dir"
"${fifo[@]}" pulseaudio --daemonize=no --exit-idle-time=-1 --system=false -n --use-pid-file=no \
  --log-target=stderr --log-level=error \
  --load="module-null-sink sink_name=seqc_null rate=44100 norewinds=1" \
  --load="module-native-protocol-unix socket=$dir/native auth-anonymous=1" \
  2> >(grep -v "not intended to be run as root" >&2) &
server=$!
cleanup() {
  kill "$server" 2>/dev/null || true
  wait "$server" 2>/dev/null || true
  rm -rf "$dir"
}
trap cleanup EXIT
export PULSE_SERVER="unix:$dir/native"
for _ in $(seq 200); do
  pactl info >/dev/null 2>&1 && break
  sleep 0.05
done
pactl set-default-sink seqc_null >/dev/null
"${fifo[@]}" "$@"
