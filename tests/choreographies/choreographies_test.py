#!/usr/bin/python3
"""Five choreographies a choreographer would write, run through every command a person runs
on them: check --strict, compile, simulate, plot and upload (the show through `seqc show`),
on the emulators. The expected lengths and send times are worked out from the files' beats
here, not read from seqc.
Usage: choreographies_test.py SEQC"""
import csv
import io
import json
import os
import subprocess
import sys
import tempfile

seqc = sys.argv[1]
here = os.path.dirname(os.path.abspath(__file__))
problems = []


def run(*args):
    return subprocess.run([seqc, *args], capture_output=True, text=True, cwd=here, timeout=120)


def beats_ms(beats, bpm):
    return beats * 60000 / bpm


# file, port, length in ms from its beats
solos = [
    # 16 bars of 4/4 at 128 bpm
    ("xarm-dance-128.yaml", "emu:xarm", beats_ms(64, 128)),
    # 2 + 2 + 4 x (2 + 2) + 2 + 2 beats, then two bars of 4/4: 32 beats at 120 bpm
    ("hexapod-tripod.yaml", "emu:xarm", beats_ms(32, 120)),
    # a 3/4 bar, four bars of 3/4, one beat of bar 6 and then two: 18 beats at 96 bpm
    ("lsc16-humanoid.yaml", "emu:xarm", beats_ms(18, 96)),
    # seven bars of 4/4 at 128 bpm
    ("show-arm.yaml", "emu:xarm", beats_ms(28, 128)),
]
assert beats_ms(64, 128) == 30000 and beats_ms(18, 96) == 11250

with tempfile.TemporaryDirectory() as tmp:
    for name, port, length in solos:
        r = run("check", "--strict", name)
        if r.returncode != 0 or r.stderr:
            problems.append(f"{name}: check --strict: {r.returncode} {r.stdout}{r.stderr}")
            continue
        # "name: N/1020 actions, 30.000 s, ..."
        actions = int(r.stdout.split(": ", 1)[1].split("/", 1)[0])
        if f", {length / 1000:.3f} s," not in r.stdout:
            problems.append(f"{name}: check says {r.stdout.strip()}, expected {length / 1000:.3f} s")
        hexfile = os.path.join(tmp, name + ".hex")
        r = run("compile", name, "-o", hexfile)
        if r.returncode != 0 or not os.path.getsize(hexfile):
            problems.append(f"{name}: compile: {r.returncode} {r.stderr}")
        r = run("simulate", name, "-o", "-")
        rows = list(csv.reader(io.StringIO(r.stdout)))
        if r.returncode != 0 or float(rows[-1][0]) != length:
            problems.append(f"{name}: simulate ends at {rows[-1][0] if rows else '?'} ms, "
                            f"expected {length}")
        svg = os.path.join(tmp, name + ".svg")
        r = run("plot", name, "-o", svg)
        if r.returncode != 0 or "<svg" not in open(svg).read(200):
            problems.append(f"{name}: plot: {r.returncode} {r.stderr}")
        r = run("upload", name, "--port", port)
        if r.returncode != 0 or f"acknowledged {actions} actions" not in r.stderr:
            problems.append(f"{name}: upload: {r.returncode} {r.stderr[-300:]}")

    # The car's half: a drive on beats 2, 3 and 4 of each four-beat cycle. A beat at 128 bpm is
    # 468.75 ms; each send time is the exact beat rounded once (halves away from zero): beats 1,
    # 2, 3 at 468.75, 937.5, 1406.25 ms, and beats 5, 6, 7 at 2343.75, 2812.5, 3281.25 ms.
    r = run("check", "--strict", "show-car.yaml")
    if r.returncode != 0 or "13.125 s" not in r.stdout:
        problems.append(f"show-car.yaml: check --strict: {r.returncode} {r.stdout}{r.stderr}")
    r = run("compile", "show-car.yaml", "--emit", "json")
    car = json.loads(r.stdout)
    stop = "ff fe 03 08 01 00 00 00 00 00 00 01 0d"  # Rocker 0, 0, 0
    drives = [f["at_ms"] for f in car["frames"] if f["hex"].startswith("ff fe 03") and f["hex"] != stop]
    if car["duration_ms"] != beats_ms(28, 128):
        problems.append(f"show-car.yaml: {car['duration_ms']} ms, expected {beats_ms(28, 128)}")
    if drives[:3] != [469, 938, 1406] or drives[3:6] != [2344, 2813, 3281]:
        problems.append(f"show-car.yaml: drives at {drives[:6]}, expected 469, 938, 1406, "
                        "2344, 2813, 3281")
    r = run("simulate", "show-car.yaml", "-o", "-")
    if r.returncode != 0 or not r.stdout.startswith("time_ms,x,y,z,pan,tilt"):
        problems.append(f"show-car.yaml: simulate: {r.returncode} {r.stderr}")
    svg = os.path.join(tmp, "car.svg")
    r = run("plot", "show-car.yaml", "-o", svg)
    if r.returncode != 0 or "<svg" not in open(svg).read(200):
        problems.append(f"show-car.yaml: plot: {r.returncode} {r.stderr}")

    # The show: both performers stored or streamed on the emulators, started at one instant.
    r = run("show", "arm-car-show.yaml")
    if r.returncode != 0 or "start skew between performers" not in r.stderr:
        problems.append(f"arm-car-show.yaml: show: {r.returncode} {r.stderr[-400:]}")

for p in problems:
    print("FAIL:", p, file=sys.stderr)
if problems:
    sys.exit(1)
print(f"{len(solos) + 1} choreographies and a show: check, compile, simulate, plot, upload")
