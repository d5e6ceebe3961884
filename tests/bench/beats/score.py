#!/usr/bin/python3
"""How well `seqc beats` hears real music: its beats, downbeats, tempo and meter against the
truth that scripts/beats-data.sh reads from Debian's Hydrogen and LMMS demo projects.

  score.py [--seqc PATH] [--data DIR] [--set tune|held-out|all] [--json] [--min-f X]

For each song of the set (tests/bench/beats/sets.txt) that DIR holds, runs
`seqc beats DIR/NAME.wav --beats-out TMP` and scores, with mir_eval (Debian's python3-mir-eval):

- beat F-measure (70 ms window), CMLt and AMLt (mir_eval.beat; no 5 s trim: the truth starts
  where the music starts, and finding bar 1 there is part of the job);
- downbeat F-measure: the POS == 1 beats against the truth's, with mir_eval.beat.f_measure;
- tempo: the printed `tempo:` within 0.1 % of the project's bpm, within 4 %, or within 4 % of
  x2, x0.5, x3 or x2/3 of it (an octave error, flagged apart);
- meter: the printed `meter:` against the project's;
- x real time: the song's length over seqc's wall time.

A song seqc refuses ("no steady beat", exit 1) or fails on scores 0 in the means and is counted
apart. It prints a Markdown table per set and, with --json, a JSON summary. It measures and does
not gate: the exit status is 0 unless the harness itself fails (2), or --min-f X is given and a
set's mean beat F-measure is below X (1). --skip-code N exits N when there is nothing to score
(no data, or no mir_eval), so a ctest can report the benchmark skipped; without it, that is a
harness failure.
"""

import argparse
import json
import os
import re
import resource
import subprocess
import sys
import tempfile
import time
import warnings
import wave

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
SETS = ("tune", "held-out")
# An octave error: seqc's tempo over the project's, within 4 % of one of these.
OCTAVES = (("x2", 2.0), ("x0.5", 0.5), ("x3", 3.0), ("x2/3", 2.0 / 3.0))
EXACT = 0.001
NEAR = 0.04
# Each run of seqc is held to 3 GB of address space and this many seconds, as any experiment
# with an input seqc did not write.
RUN_LIMIT_S = 300


class HarnessError(Exception):
    pass


def read_sets(path):
    """{set name: [song names]} from sets.txt (`SET NAME` a line, `#` comments)."""
    sets = {s: [] for s in SETS}
    with open(path) as f:
        for number, line in enumerate(f, 1):
            line = line.split("#", 1)[0].strip()
            if not line:
                continue
            parts = line.split()
            if len(parts) != 2 or parts[0] not in sets:
                raise HarnessError(f"{path}:{number}: expected `tune NAME` or `held-out NAME`")
            sets[parts[0]].append(parts[1])
    return sets


def read_beats(path):
    """[(time, position)] of a TIME<TAB>POS file (position 0 when a line has none)."""
    beats = []
    with open(path) as f:
        for number, line in enumerate(f, 1):
            fields = line.split()
            if not fields:
                continue
            try:
                beats.append((float(fields[0]), int(fields[1]) if len(fields) > 1 else 0))
            except ValueError:
                raise HarnessError(f"{path}:{number}: not TIME<TAB>POS: {line.rstrip()!r}")
    return beats


def wav_seconds(path):
    with wave.open(path) as w:
        return w.getnframes() / w.getframerate()


def limit_memory():
    resource.setrlimit(resource.RLIMIT_AS, (3_000_000_000, 3_000_000_000))


def run_seqc(seqc, song, beats_out):
    """(exit status, stdout, stderr, wall seconds) of `seqc beats SONG --beats-out FILE`."""
    start = time.monotonic()
    try:
        done = subprocess.run([seqc, "beats", song, "--beats-out", beats_out],
                              capture_output=True, text=True, timeout=RUN_LIMIT_S,
                              preexec_fn=limit_memory)
    except subprocess.TimeoutExpired:
        return None, "", f"no answer within {RUN_LIMIT_S} s", time.monotonic() - start
    except OSError as err:
        raise HarnessError(f"cannot run {seqc}: {err}")
    return done.returncode, done.stdout, done.stderr, time.monotonic() - start


def parse_block(stdout):
    """(tempo, meter) printed in the music: block, None where absent."""
    tempo = re.search(r"^\s*tempo:\s*([0-9.]+)\s*$", stdout, re.M)
    meter = re.search(r"^\s*meter:\s*(\d+/\d+)\s*$", stdout, re.M)
    return (float(tempo.group(1)) if tempo else None, meter.group(1) if meter else None)


def tempo_verdict(tempo, bpm):
    """(relative error, flag): flag `0.1%`, `4%`, an octave name, or `off`."""
    if tempo is None:
        return None, "none"
    error = abs(tempo - bpm) / bpm
    if error <= EXACT:
        return error, "0.1%"
    if error <= NEAR:
        return error, "4%"
    for name, ratio in OCTAVES:
        if abs(tempo - bpm * ratio) / (bpm * ratio) <= NEAR:
            return error, name
    return error, "off"


def audio_path(data, name):
    """DIR/NAME.wav (a render) or DIR/NAME.ogg (a band recording, linked by
    scripts/beats-truth-charts.py)."""
    wav = os.path.join(data, name + ".wav")
    ogg = os.path.join(data, name + ".ogg")
    return ogg if not os.path.exists(wav) and os.path.exists(ogg) else wav


def score_song(mir_beat, np, seqc, data, name):
    wav = audio_path(data, name)
    meta = json.load(open(os.path.join(data, name + ".json")))
    truth = read_beats(os.path.join(data, name + ".truth"))
    # A recording that is not WAV (the band recordings, Ogg Vorbis) has its length in its JSON.
    seconds = meta["seconds"] if "seconds" in meta else wav_seconds(wav)
    row = {"song": name, "bpm": meta["bpm"], "meter": meta["meter"],
           "seconds": seconds, "status": "ok"}
    with tempfile.TemporaryDirectory(prefix="seqc-beats-score-") as tmp:
        out = os.path.join(tmp, name + ".beats")
        status, stdout, stderr, wall = run_seqc(seqc, wav, out)
        row["wall_s"] = wall
        row["x_real_time"] = row["seconds"] / wall if wall > 0 else None
        if status == 2 and "beats-out" in stderr:
            raise HarnessError(f"{seqc} has no --beats-out option: {stderr.strip()}")
        if status == 0:
            if not os.path.exists(out):
                raise HarnessError(f"{seqc} exited 0 but wrote no {out}")
            estimate = read_beats(out)
        else:
            estimate = []
            refused = status == 1 and "no steady beat" in stderr
            row["status"] = "refused" if refused else f"failed ({status})"
            row["message"] = stderr.strip().splitlines()[-1] if stderr.strip() else ""
    tempo, meter = parse_block(stdout) if status == 0 else (None, None)
    row["tempo"], row["meter_found"] = tempo, meter
    row["tempo_error"], row["tempo_flag"] = tempo_verdict(tempo, meta["bpm"])
    row["meter_right"] = None if meta["meter"] == "mixed" else meter == meta["meter"]
    ref = np.array([t for t, _ in truth])
    est = np.array(sorted(t for t, _ in estimate))
    ref_down = np.array([t for t, p in truth if p == 1])
    est_down = np.array(sorted(t for t, p in estimate if p == 1))
    row["beat_f"] = float(mir_beat.f_measure(ref, est))
    _, cmlt, _, amlt = mir_beat.continuity(ref, est)
    row["cmlt"], row["amlt"] = float(cmlt), float(amlt)
    row["downbeat_f"] = float(mir_beat.f_measure(ref_down, est_down))
    row["beats_found"] = len(estimate)
    row["beats_truth"] = len(truth)
    return row


def summarize(rows):
    n = len(rows)
    if not n:
        return {"songs": 0}

    def mean(key):
        return sum(r[key] for r in rows) / n

    meters = [r["meter_right"] for r in rows if r["meter_right"] is not None]
    audio = sum(r["seconds"] for r in rows)
    wall = sum(r["wall_s"] for r in rows)
    return {
        "songs": n,
        "beat_f": mean("beat_f"),
        "cmlt": mean("cmlt"),
        "amlt": mean("amlt"),
        "downbeat_f": mean("downbeat_f"),
        "tempo_within_0.1%": sum(r["tempo_flag"] == "0.1%" for r in rows) / n,
        "tempo_within_4%": sum(r["tempo_flag"] in ("0.1%", "4%") for r in rows) / n,
        "octave_errors": {name: sum(r["tempo_flag"] == name for r in rows)
                          for name, _ in OCTAVES},
        "meter_right": sum(meters) / len(meters) if meters else None,
        "refused": sum(r["status"] == "refused" for r in rows),
        "failed": sum(r["status"].startswith("failed") for r in rows),
        "audio_s": audio,
        "wall_s": wall,
        "x_real_time": audio / wall if wall > 0 else None,
    }


def markdown(set_name, rows, summary):
    lines = [f"### {set_name}: {summary['songs']} songs", "",
             "| song | bpm | tempo found | tempo | meter | beat F | CMLt | AMLt | downbeat F "
             "| x real time |",
             "| --- | ---: | ---: | --- | --- | ---: | ---: | ---: | ---: | ---: |"]
    for r in rows:
        if r["status"] != "ok":
            found = r["status"]
        else:
            found = f"{r['tempo']:g}" if r["tempo"] is not None else "no tempo:"
        if r["tempo_flag"] in ("0.1%", "4%"):
            verdict = f"within {r['tempo_flag']} ({100 * r['tempo_error']:.2f} %)"
        elif r["tempo_flag"] == "none":
            verdict = "-"
        elif r["tempo_flag"] == "off":
            verdict = f"off ({100 * r['tempo_error']:.1f} %)"
        else:
            verdict = f"**{r['tempo_flag']}**"
        if r["meter_right"] is None:
            meter = r["meter"]
        elif r["meter_right"]:
            meter = r["meter"] + " ok"
        else:
            meter = f"{r['meter']}, found {r['meter_found'] or 'none'}"
        xrt = f"{r['x_real_time']:.0f}" if r["x_real_time"] else "-"
        lines.append(f"| {r['song']} | {r['bpm']:g} | {found} | {verdict} | {meter} "
                     f"| {r['beat_f']:.3f} | {r['cmlt']:.3f} | {r['amlt']:.3f} "
                     f"| {r['downbeat_f']:.3f} | {xrt} |")
    if rows:
        s = summary
        meter = f"{100 * s['meter_right']:.0f} % right" if s["meter_right"] is not None else "-"
        xrt = f"{s['x_real_time']:.0f}" if s["x_real_time"] else "-"
        lines.append(f"| **mean** | | | {100 * s['tempo_within_0.1%']:.0f} % within 0.1 % "
                     f"| {meter} | {s['beat_f']:.3f} | {s['cmlt']:.3f} | {s['amlt']:.3f} "
                     f"| {s['downbeat_f']:.3f} | {xrt} |")
        octaves = ", ".join(f"{k} {v}" for k, v in s["octave_errors"].items() if v) or "none"
        lines += ["", f"Tempo within 0.1 %: {100 * s['tempo_within_0.1%']:.0f} % of the songs "
                  f"(within 4 %: {100 * s['tempo_within_4%']:.0f} %; octave errors: {octaves}). "
                  f"Refused (no steady beat): {s['refused']}; failed: {s['failed']}. "
                  f"{s['audio_s']:.0f} s of audio in {s['wall_s']:.1f} s."]
    return "\n".join(lines)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seqc", default=os.path.join(ROOT, "build", "runtime", "cli", "seqc"),
                        help="the seqc to measure (default: the build's)")
    parser.add_argument("--data", default=os.path.join(ROOT, "build", "beats-data"),
                        help="what scripts/beats-data.sh wrote (default: build/beats-data)")
    parser.add_argument("--set", choices=SETS + ("all",), default="all",
                        help="which songs (default: both sets, a table each)")
    parser.add_argument("--sets-file", default=os.path.join(HERE, "sets.txt"),
                        help="the sets' song names (default: tests/bench/beats/sets.txt)")
    parser.add_argument("--json", action="store_true", help="also print a JSON summary")
    parser.add_argument("--min-f", type=float, help="exit 1 when a set's mean beat F is below")
    parser.add_argument("--skip-code", type=int,
                        help="exit with this code when there is nothing to score")
    args = parser.parse_args(argv[1:])

    def nothing(reason):
        print(f"score.py: {reason}; nothing scored")
        return args.skip_code if args.skip_code is not None else 2

    try:
        import numpy as np
        from mir_eval import beat as mir_beat

        # An empty estimate (a refusal) scores 0; mir_eval's warning about it says nothing more.
        warnings.filterwarnings("ignore", category=UserWarning, module="mir_eval")
    except ImportError as err:
        if args.skip_code is not None:
            return nothing(f"no mir_eval ({err}): apt-get install python3-mir-eval")
        raise HarnessError(f"no mir_eval ({err}): apt-get install python3-mir-eval")
    sets = read_sets(args.sets_file)
    chosen = SETS if args.set == "all" else (args.set,)
    if not os.path.isdir(args.data):
        return nothing(f"no data in {args.data} (scripts/beats-data.sh makes it)")
    if not os.access(args.seqc, os.X_OK):
        raise HarnessError(f"{args.seqc} is not an executable")
    results, absent = {}, []
    for set_name in chosen:
        rows = []
        for name in sets[set_name]:
            files = [audio_path(args.data, name)] + [os.path.join(args.data, name + ext)
                                                     for ext in (".truth", ".json")]
            if not all(os.path.exists(f) for f in files):
                absent.append(name)
                continue
            rows.append(score_song(mir_beat, np, args.seqc, args.data, name))
        results[set_name] = (rows, summarize(rows))
    if absent:
        print(f"score.py: {len(absent)} songs of the sets are not in {args.data} (not rendered?), "
              f"skipped: {' '.join(absent)}", file=sys.stderr)
    if not any(rows for rows, _ in results.values()):
        return nothing(f"no song of {args.sets_file} in {args.data}")
    for set_name, (rows, summary) in results.items():
        print(markdown(set_name, rows, summary))
        print()
    if args.json:
        print(json.dumps({"seqc": args.seqc, "data": args.data,
                          "sets": {k: {"summary": s, "songs": r} for k, (r, s) in results.items()}},
                         indent=1))
    if args.min_f is not None:
        low = [k for k, (rows, s) in results.items() if rows and s["beat_f"] < args.min_f]
        if low:
            print(f"score.py: mean beat F below {args.min_f} in: {', '.join(low)}")
            return 1
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv))
    except HarnessError as err:
        print(f"score.py: error: {err}", file=sys.stderr)
        sys.exit(2)
