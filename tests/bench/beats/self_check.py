#!/usr/bin/python3
"""The real-music benchmark's own tools on inputs whose answers are written here, so a bug in
them shows without the rendered songs: scripts/beats-truth.py on two hand-made projects
(fixtures/) and on refused ones, and score.py on a made-up data folder answered by
stand_in_seqc.py, whose five ways of being wrong each have known scores.

Usage: self_check.py REPO_ROOT. Exit 0 when all hold, 1 otherwise, 77 (skipped) when the
truth checks pass but mir_eval is not installed for the scorer's."""

import json
import os
import struct
import subprocess
import sys
import tempfile
import wave
import zlib

root = os.path.abspath(sys.argv[1])
here = os.path.join(root, "tests", "bench", "beats")
truth_py = os.path.join(root, "scripts", "beats-truth.py")
problems = []


def run(*args):
    return subprocess.run([sys.executable, *args], capture_output=True, text=True)


def expect(what, got, want):
    if got != want:
        problems.append(f"{what}:\n  got  {got!r}\n  want {want!r}")


# --- the truth writer ----------------------------------------------------------------------

# 120 bpm, a beat 0.5 s: the first bar is empty, so the truth starts at bar 2 (tick 192); each
# column starts a bar whatever its length (4, 3, then 4 beats); the last note is at tick
# 528 + 96 = 624 and its beat is kept; the note at 150 lies past its 144-tick pattern.
MIXED = """# bpm 120 meter mixed
2.000\t1
2.500\t2
3.000\t3
3.500\t4
4.000\t1
4.500\t2
5.000\t3
5.500\t1
6.000\t2
6.500\t3
"""
# 150 bpm in 3/4, a beat 0.4 s, a bar 144 ticks: the muted track's note at 0 does not count,
# so the truth starts at bar 2 (the lead's first note is at 192); the beat/bassline's kick
# (a 192-tick pattern, so a two-bar loop) plays at 432 and 720, the last note.
THREE_FOUR = """# bpm 150 meter 3/4
1.200\t1
1.600\t2
2.000\t3
2.400\t1
2.800\t2
3.200\t3
3.600\t1
4.000\t2
4.400\t3
4.800\t1
5.200\t2
5.600\t3
6.000\t1
"""
mixed = run(truth_py, "show", os.path.join(here, "fixtures", "mixed-bars.h2song"))
expect("truth of fixtures/mixed-bars.h2song", mixed.stdout, MIXED)
mmp_path = os.path.join(here, "fixtures", "three-four.mmp")
three = run(truth_py, "show", mmp_path)
expect("truth of fixtures/three-four.mmp", three.stdout, THREE_FOUR)

with tempfile.TemporaryDirectory(prefix="beats-self-check-") as tmp:
    xml = open(mmp_path, "rb").read()
    # .mmpz: the XML's length as 4 bytes big-endian, then the XML compressed with zlib.
    mmpz = os.path.join(tmp, "three-four.mmpz")
    with open(mmpz, "wb") as f:
        f.write(struct.pack(">I", len(xml)) + zlib.compress(xml))
    expect("truth of the same project as .mmpz", run(truth_py, "show", mmpz).stdout, THREE_FOUR)
    refused = {
        "tempo automation": xml.decode().replace(
            '<head timesig_numerator="3" timesig_denominator="4" bpm="150" mastervol="100" '
            'masterpitch="0"/>',
            '<head timesig_numerator="3" timesig_denominator="4"><bpm value="150" id="7"/></head>')
        .replace('<trackcontainer type="song">',
                 '<trackcontainer type="song"><track type="5" name="a" muted="0">'
                 '<automationpattern pos="0" len="192"><time pos="0" value="150"/>'
                 '<time pos="96" value="160"/><object id="7"/></automationpattern></track>'),
        "meter 8/4: the bar grid is unclear": xml.decode().replace(
            'timesig_numerator="3"', 'timesig_numerator="8"'),
    }
    for reason, text in refused.items():
        path = os.path.join(tmp, "refused.mmp")
        with open(path, "w") as f:
            f.write(text)
        done = run(truth_py, "show", path)
        expect(f"exit status of a project with {reason}", done.returncode, 1)
        expect(f"why a project with {reason} is left out", done.stderr,
               f"excluded: {path}: {reason}\n")

    # --- the scorer ------------------------------------------------------------------------
    try:
        import mir_eval  # noqa: F401
    except ImportError:
        for p in problems:
            print("self_check: " + p)
        print("self_check: no mir_eval (apt-get install python3-mir-eval): scorer not checked")
        sys.exit(1 if problems else 77)

    # stand_in_seqc.py is wrong in the way the song's name ends with.
    modes = {f"song-{m}": m for m in ("perfect", "double", "late", "bar-off", "refuse")}
    data = os.path.join(tmp, "data")
    os.mkdir(data)
    for name in modes:
        with wave.open(os.path.join(data, name + ".wav"), "wb") as w:
            w.setnchannels(1)
            w.setsampwidth(2)
            w.setframerate(8000)
            w.writeframes(b"\0\0" * 8000 * 20)  # 20 s
        with open(os.path.join(data, name + ".truth"), "w") as f:
            for k in range(36):  # 9 bars of 4/4 at 120 bpm from 1 s
                f.write(f"{1 + 0.5 * k:.3f}\t{k % 4 + 1}\n")
        with open(os.path.join(data, name + ".json"), "w") as f:
            json.dump({"bpm": 120.0, "meter": "4/4"}, f)
    sets = os.path.join(tmp, "sets.txt")
    with open(sets, "w") as f:
        f.write("# all in one set\n" + "".join(f"tune {n}\n" for n in modes))
    score = [os.path.join(here, "score.py"), "--seqc", os.path.join(here, "stand_in_seqc.py"),
             "--data", data, "--sets-file", sets, "--set", "tune"]
    done = run(*score, "--json")
    expect("score.py's exit status", done.returncode, 0)
    report = json.loads(done.stdout[done.stdout.index("\n{\n"):]) if "\n{\n" in done.stdout else {}
    songs = {r["song"]: r for r in report.get("sets", {}).get("tune", {}).get("songs", [])}
    # (beat F, CMLt, AMLt, downbeat F, tempo flag, meter right, status), all known in advance:
    # double has 72 beats where 36 are right (F 2/3) at twice the tempo, which only AMLt
    # allows: 71 of its 72 beats (the half-beat after the last one has no partner); late is
    # past both the 70 ms window and the continuity's 17.5 % of a beat.
    want = {
        "perfect": (1.0, 1.0, 1.0, 1.0, "0.1%", True, "ok"),
        "double": (0.667, 0.0, 0.986, 1.0, "x2", False, "ok"),
        "late": (0.0, 0.0, 0.0, 0.0, "0.1%", True, "ok"),
        "bar-off": (1.0, 1.0, 1.0, 0.0, "0.1%", True, "ok"),
        "refuse": (0.0, 0.0, 0.0, 0.0, "none", False, "refused"),
    }
    for name, mode in modes.items():
        r = songs.get(name)
        if r is None:
            problems.append(f"score.py did not score {name} ({mode}): {done.stdout}{done.stderr}")
            continue
        got = (round(r["beat_f"], 3), round(r["cmlt"], 3), round(r["amlt"], 3),
               round(r["downbeat_f"], 3), r["tempo_flag"], r["meter_right"], r["status"])
        expect(f"scores of {name} ({mode})", got, want[mode])
    summary = report.get("sets", {}).get("tune", {}).get("summary", {})
    expect("share within 0.1 %", summary.get("tempo_within_0.1%"), 0.6)
    expect("octave errors", summary.get("octave_errors"), {"x2": 1, "x0.5": 0, "x3": 0, "x2/3": 0})
    expect("refusals", summary.get("refused"), 1)
    # The means: beat F (1 + 2/3 + 0 + 1 + 0) / 5, CMLt 2/5, AMLt (1 + 71/72 + 1) / 5,
    # downbeat F 2/5; perfect, late and bar-off have the tempo and the meter.
    expect("mean row", "| **mean** | | | 60 % within 0.1 % | 60 % right | 0.533 | 0.400 "
           "| 0.597 | 0.400 |" in done.stdout, True)
    expect("--min-f 0.5 with a mean beat F of 0.533", run(*score, "--min-f", "0.5").returncode, 0)
    expect("--min-f 0.6 with a mean beat F of 0.533", run(*score, "--min-f", "0.6").returncode, 1)
    nothing = [os.path.join(here, "score.py"), "--data", os.path.join(tmp, "none")]
    expect("no data, with --skip-code 77", run(*nothing, "--skip-code", "77").returncode, 77)
    expect("no data, without it", run(*nothing).returncode, 2)

for p in problems:
    print("self_check: " + p)
print(f"self_check: {'FAILED' if problems else 'ok'}: truth writer on 2 projects, 1 compressed, "
      f"2 refused; scorer on 5 known answers")
sys.exit(1 if problems else 0)
