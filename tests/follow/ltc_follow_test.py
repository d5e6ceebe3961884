#!/usr/bin/env python3
"""`seqc follow --ltc` end to end, on the timecode libltc encoded (ltc_signal.py's show run,
25 fps at 48 kHz): one second from 00:59:59:00, four seconds after 01:00:00:00, a one-second
dropout, two seconds, a jump to 01:10:00:00, two seconds, three seconds of silence.

The arm: tests/data/walk-joints.yaml on the in-process emu:xarm, `--start 01:00:00:00 --once`.
The WAV is read at its real pace from the moment seqc says it follows, so:
- the group is stored once the timecode locks (4 frames, 160 ms in), before the start;
- it is started when the timecode reaches 01:00:00:00, one second into the file: seqc's
  "started group 0" line comes 1000 ms after its "following" line (within 80 ms: the line's own
  way through a pipe, the frame's 40 ms and the 4 frames of re-lock are not in it, but a shared
  machine's scheduling is);
- the dropout is ridden out (no stop before the silence at the end), and the stop comes once the
  timecode has been silent for 2 s; with --once seqc then exits 0, having sent the stop.
The car: examples/car-dance.yaml on emu:raspblock, the same file: it plans its stream at the lock,
starts at 01:00:00:00 and stops. Prints the start skew of each.

Usage: ltc_follow_test.py SEQC SOURCE_DIR LTC_DIR
"""
import os
import subprocess
import sys
import threading
import time


def fail(message):
    print("ltc_follow_test: " + message, file=sys.stderr)
    sys.exit(1)


class Lines:
    """A process's stderr, each line with the instant it arrived."""

    def __init__(self, stream):
        self.lines = []
        self.thread = threading.Thread(target=self._read, args=(stream,), daemon=True)
        self.thread.start()

    def _read(self, stream):
        for line in iter(stream.readline, ""):
            self.lines.append((time.monotonic(), line.rstrip("\n")))

    def first(self, text):
        for t, line in self.lines:
            if text in line:
                return t, line
        return None


def follow(seqc, source, wav, dance, port):
    proc = subprocess.Popen([seqc, "follow", dance, "--ltc", wav, "--start", "01:00:00:00",
                             "--port", port, "--once"], cwd=source, stderr=subprocess.PIPE,
                            text=True, bufsize=1)
    lines = Lines(proc.stderr)
    try:
        code = proc.wait(timeout=60)
    except subprocess.TimeoutExpired:
        proc.kill()
        fail("follow did not end within 60 s")
    lines.thread.join(timeout=5)
    return code, lines


def main():
    seqc, source, ltc_dir = sys.argv[1:4]
    wav = os.path.join(ltc_dir, "ltc-show-25-48000.wav")
    if not os.path.exists(wav):
        print("no libltc signals: skipped")
        return 77

    code, lines = follow(seqc, source, wav, "tests/data/walk-joints.yaml", "emu:xarm")
    text = "\n".join(line for _, line in lines.lines)
    if code != 0:
        fail("follow (arm) exited %d:\n%s" % (code, text))
    following = lines.first("seqc: following timecode on")
    stored = lines.first("stored")
    started = lines.first("started group 0")
    stopped = lines.first("stop (")
    if not (following and stored and started and stopped):
        fail("the arm's run lacks a following, stored, started or stop line:\n" + text)
    if not stored[0] <= started[0]:
        fail("the group was started before it was stored:\n" + text)
    skew = (started[0] - following[0] - 1.0) * 1000
    if not -40 <= skew <= 80:
        fail("the group started %.1f ms from 01:00:00:00 (1 s into the file):\n%s" % (skew, text))
    # The dropout (4 s to 5 s after the start) freewheels; the stop follows the final silence:
    # 10 s of timecode, then 2 s of freewheel.
    if stopped[0] - following[0] < 11.5:
        fail("the stop came %.2f s in, before the timecode ended:\n%s"
             % (stopped[0] - following[0], text))
    if "sent the stop" not in text:
        fail("the arm was not sent the stop:\n" + text)
    print("arm: started %.1f ms from the timecode's 01:00:00:00, stopped %.2f s in" %
          (skew, stopped[0] - following[0]))

    code, lines = follow(seqc, source, wav, "examples/car-dance.yaml", "emu:raspblock")
    text = "\n".join(line for _, line in lines.lines)
    if code != 0:
        fail("follow (car) exited %d:\n%s" % (code, text))
    following = lines.first("seqc: following timecode on")
    planned = lines.first("planned")
    start = lines.first("start at 0.000 s")
    if not (following and planned and start and "sent the stop" in text):
        fail("the car's run lacks a plan, a start at 0 or the stop:\n" + text)
    skew = (start[0] - following[0] - 1.0) * 1000
    if not -40 <= skew <= 80:
        fail("the car started %.1f ms from 01:00:00:00:\n%s" % (skew, text))
    print("car: started %.1f ms from the timecode's 01:00:00:00" % skew)
    print("1 passed, 0 failed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
