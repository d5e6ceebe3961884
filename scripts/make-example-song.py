#!/usr/bin/env python3
"""Writes examples/music/neon-pulse.wav: a 20-second generated song to try `seqc beats` on
(docs/music.md). 128 BPM, 4/4, bar 1 beat 1 at 0.750 s after a lead-in of quiet noise; kick on
1 and 3, snare on 2 and 4, hi-hats on the eighths and a bass note on every bar's first beat, all
made from decaying sines and noise. Mono, 22050 Hz, 16-bit (under 1 MB). Python's standard
library only, and the same bytes every run (a fixed seed).

Usage: scripts/make-example-song.py [OUT.wav]"""
import math
import os
import random
import struct
import sys
import wave

RATE = 22050
TEMPO = 128.0
LEAD_IN = 0.75
BARS = 10
BEAT = 60.0 / TEMPO


def add(mix, at, length, voice):
    start = int(round(at * RATE))
    for k in range(int(length * RATE)):
        i = start + k
        if 0 <= i < len(mix):
            mix[i] += voice(k / RATE)


def kick(mix, at, level, rng):
    # A sine falling from 150 Hz to 50 Hz, decaying over 120 ms, with a 2 ms click.
    def voice(t):
        phase = 2 * math.pi * (50 * t + 100 * 0.03 * (1 - math.exp(-t / 0.03)))
        click = 0.3 * rng.gauss(0, 1) if t < 0.002 else 0.0
        return level * (0.8 * math.exp(-t / 0.12) * math.sin(phase) + click)
    add(mix, at, 0.35, voice)


def snare(mix, at, level, rng):
    add(mix, at, 0.25, lambda t: level * (0.35 * math.exp(-t / 0.06) * rng.gauss(0, 1) +
                                          0.3 * math.exp(-t / 0.05) * math.sin(2 * math.pi * 180 * t)))


def hat(mix, at, level, rng):
    previous = [0.0]

    def voice(t):
        white = rng.gauss(0, 1)
        bright = white - previous[0]  # a first difference: mostly high frequencies
        previous[0] = white
        return level * 0.12 * math.exp(-t / 0.015) * bright
    add(mix, at, 0.06, voice)


def bass(mix, at, length, freq):
    add(mix, at, length, lambda t: 0.3 * math.exp(-t / 0.6) * math.sin(2 * math.pi * freq * t))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.normpath(os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "examples", "music", "neon-pulse.wav"))
    rng = random.Random(128)
    end = LEAD_IN + BARS * 4 * BEAT + 1.0
    mix = [0.002 * rng.gauss(0, 1) for _ in range(int(end * RATE))]
    notes = [55.0, 65.41, 49.0, 58.27]  # A1 C2 G1 Bb1
    for i in range(BARS * 4):
        at = LEAD_IN + i * BEAT
        bar, beat = divmod(i, 4)
        if beat == 0:
            kick(mix, at, 1.0, rng)
            bass(mix, at, 4 * BEAT, notes[bar % 4])
        elif beat == 2:
            kick(mix, at, 0.6, rng)
        else:
            snare(mix, at, 1.0, rng)
        hat(mix, at, 1.0, rng)
        hat(mix, at + BEAT / 2, 0.7, rng)
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    frames = b"".join(struct.pack("<h", int(max(-1.0, min(1.0, s)) * 32767)) for s in mix)
    with wave.open(out, "wb") as w:
        w.setnchannels(1)
        w.setsampwidth(2)
        w.setframerate(RATE)
        w.writeframes(frames)
    print(f"{out}: {len(mix) / RATE:.1f} s, {TEMPO:g} BPM 4/4, bar 1 at {LEAD_IN:.3f} s")


if __name__ == "__main__":
    main()
