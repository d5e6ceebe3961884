#!/usr/bin/python3
"""A stand-in for `seqc beats SONG --beats-out FILE`, to check score.py itself: it does not
listen, it copies the truth beside SONG (NAME.truth, NAME.json) and spoils it in one of five known
ways chosen from the song's name (a name ending in -MODE gets that one), so every score it gets
is known in advance:

  perfect   the truth itself: beat, CMLt, AMLt and downbeat F 1, tempo within 0.1 %
  double    a beat between every two (tempo x2, bars of twice the beats): F 0.667,
            CMLt 0, AMLt about 1, downbeat F 1
  late      every beat 100 ms late (past the 70 ms window): every score 0, tempo within 0.1 %
  bar-off   the bar lines one beat early: beat F 1, downbeat F 0
  refuse    "no steady beat found", exit 1

  score.py --seqc tests/bench/beats/stand_in_seqc.py
"""

import json
import os
import sys
import zlib

MODES = ("perfect", "double", "late", "bar-off", "refuse")


def main(argv):
    if len(argv) != 5 or argv[1] != "beats" or argv[3] != "--beats-out":
        sys.stderr.write("usage: stand_in_seqc.py beats SONG --beats-out FILE\n")
        return 2
    song, out = argv[2], argv[4]
    stem = os.path.splitext(song)[0]
    name = os.path.basename(stem)
    # A name ending in -MODE asks for that mode; any other gets one by its checksum.
    mode = next((m for m in MODES if name.endswith("-" + m)),
                MODES[zlib.crc32(name.encode()) % len(MODES)])
    meta = json.load(open(stem + ".json"))
    truth = [(float(t), int(p)) for t, p in (line.split() for line in open(stem + ".truth"))]
    if mode == "refuse":
        sys.stderr.write(f"seqc: error: {song}: no steady beat found (stand-in: {mode})\n")
        return 1
    bpm, meter = meta["bpm"], meta["meter"]
    per_bar = max(p for _, p in truth)
    if mode == "late":
        beats = [(t + 0.100, p) for t, p in truth]
    elif mode == "bar-off":
        beats = [(t, p % per_bar + 1) for t, p in truth]
    elif mode == "double":
        half = 30.0 / bpm
        beats = []
        for t, p in truth:
            beats += [(t, 2 * p - 1), (t + half, 2 * p)]
        bpm, meter = 2 * bpm, f"{2 * per_bar}/4"
    else:
        beats = truth
    with open(out, "w") as f:
        for t, p in beats:
            f.write(f"{t:.3f}\t{p}\n")
    print(f"music:\n  file: {song}\n  downbeat: {beats[0][0]:.3f}s\n  tempo: {bpm:g}\n"
          f"  meter: {meter}")
    sys.stderr.write(f"seqc: {song}: {len(beats)} beats (stand-in: {mode})\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
