#!/usr/bin/env python3
"""A 3,000-action dance, longer than one group, through `seqc emulate xarm` on a pseudo-terminal
and a real sound server: `seqc upload --run --music` stores it as chained groups and starts each
on its bar line on the song's clock.

The dance: 3,000 moves of 20 ms (base 505, 500, ...) after the song's downbeat, at 150 bpm in
4/4: a bar is 1.6 s and holds 80 actions, so a group (1,020 actions) holds 12 bars (960). Groups
0-2 hold 960 actions each and start on bars 1, 13 and 25 (0, 19.2 s and 38.4 s after the
downbeat); group 3 holds the 120 left from bar 37 (57.6 s). The emulator's stored groups and the
instants its GroupRun frames arrived (its --record) are checked against those numbers, worked out
here, not read from seqc.

Usage (under tests/music/with_pulse.sh): chained_song_pty_test.py SEQC
"""
import csv
import os
import signal
import subprocess
import sys
import tempfile
import time
import wave


def fail(message):
    print("chained_song_pty_test: " + message, file=sys.stderr)
    sys.exit(1)


def write_song(path, seconds, rate=8000):
    with wave.open(path, "wb") as w:
        w.setnchannels(1)
        w.setsampwidth(2)
        w.setframerate(rate)
        w.writeframes(b"\x00\x00" * int(seconds * rate))


def main():
    seqc = sys.argv[1]
    work = tempfile.mkdtemp(prefix="seqc-chain-")
    write_song(os.path.join(work, "song.wav"), 62)
    with open(os.path.join(work, "dance.yaml"), "w") as f:
        f.write("robot: xarm\nmusic:\n  file: song.wav\n  downbeat: 0.5s\n  tempo: 150\n"
                "  meter: 4/4\nsequence:\n  - repeat: 1500\n    do:\n"
                "      - move: {base: 505}\n        time: 20ms\n"
                "      - move: {base: 500}\n        time: 20ms\n")
    link = os.path.join(work, "xarm")
    record = os.path.join(work, "record.csv")
    groups = os.path.join(work, "groups.txt")
    emu = subprocess.Popen([seqc, "emulate", "xarm", "--baud", "0", "--link", link, "--record",
                            record, "--dump-groups", groups],
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    for _ in range(200):
        if os.path.exists(link):
            break
        time.sleep(0.01)
    else:
        emu.kill()
        fail("the emulator's terminal never appeared")
    run = subprocess.run([seqc, "upload", os.path.join(work, "dance.yaml"), "--port", link,
                          "--run", "--music"], capture_output=True, text=True, timeout=240)
    emu.send_signal(signal.SIGINT)
    emu.wait(timeout=30)
    if run.returncode != 0:
        fail("upload exited %d:\n%s" % (run.returncode, run.stderr))
    said = "stored 4 chained groups starting on bars 1, 13, 25 and 37 in groups 0-3"
    if said not in run.stderr:
        fail("upload did not say %r:\n%s" % (said, run.stderr))

    counts = {}
    with open(groups) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            fields = line.split()
            g, time_ms, servo = int(fields[0]), int(fields[2]), fields[3]
            counts[g] = counts.get(g, 0) + 1
            if time_ms != 20 or servo not in ("6=505", "6=500"):
                fail("group %d holds an action other than 20 ms of base: %s" % (g, line))
    if counts != {0: 960, 1: 960, 2: 960, 3: 120}:
        fail("stored groups hold %s actions, not 960, 960, 960 and 120" % counts)

    runs = {}
    with open(record) as f:
        for row in csv.DictReader(f):
            data = row["bytes"].replace(" ", "").lower()
            if row["status"] == "ok" and data.startswith("55550506"):
                runs[int(data[8:10], 16)] = float(row["time_s"])
    if sorted(runs) != [0, 1, 2, 3]:
        fail("GroupRun arrived for groups %s, not 0-3" % sorted(runs))
    for g, bar_s in ((1, 19.2), (2, 38.4), (3, 57.6)):
        late_ms = (runs[g] - runs[0] - bar_s) * 1000
        print("group %d started %.2f ms after its bar line (from group 0's start)" % (g, late_ms))
        if abs(late_ms) > 20:
            fail("group %d started %.2f ms off its bar line" % (g, late_ms))
    print(run.stderr)
    subprocess.run(["rm", "-rf", work])


if __name__ == "__main__":
    main()
