#!/usr/bin/env python3
"""Beat truth for the real-music benchmark of `seqc beats`, read from the songs' project files.

The songs are the demo projects that Debian's hydrogen and lmms packages ship;
scripts/beats-data.sh renders them with the packages' own renderers. This script (standard
library only) reads each project file, not the audio, so the truth is the composer's grid and
not anything seqc computed.

  beats-truth.py list                 one usable project a line: NAME<TAB>KIND<TAB>PATH
                                      (KIND hydrogen or lmms); the excluded ones with their
                                      reason on stderr as `excluded: NAME: reason`
  beats-truth.py write DIR            for every usable project whose DIR/NAME.wav exists:
                                      DIR/NAME.truth (TIME<TAB>POS a line, POS 1 = downbeat) and
                                      DIR/NAME.json ({bpm, meter, project, licence, ...});
                                      DIR/excluded.txt lists the excluded projects and why
  beats-truth.py show PROJECT         one project's truth on stdout, after `# bpm B meter M`
                                      (exit 1 with the reason when it would be excluded)

Truth rules (each is why the truth can be trusted):
- Beat k of the grid is at k * 60 / bpm seconds from the render's time 0. Both renderers start
  the render at the song's tick 0: a hand-made project with a single kick on bar 2's first tick
  at 120 BPM renders with its first non-zero sample at exactly 2.000 s (88,200 of 44,100 Hz) with
  h2cli and with `lmms render`, and there is no tempo automation in any project kept (below), so
  tick t is at t / ticks-per-beat * 60 / bpm.
- Only the span where music plays is kept: from the bar line at or before the first note to the
  end of the last note. A hit without a length (a drum sample, LMMS's step notes, Hydrogen's
  length -1) ends where it starts: what rings after it is the instrument's tail, not the music's
  pulse, and a renderer's reverb tail carries no beat. Beats inside long silences in that span are
  kept: the song's grid goes on through them.
- Projects whose tempo is automated (an automation pattern on the tempo) or whose meter or
  pattern lengths leave the bar grid unclear (a meter other than N/4 with N 2, 3, 4, 6 or 12, or
  a Hydrogen pattern that is not a whole number of beats) are excluded and listed with the
  reason. Hydrogen's pattern sizes are in ticks, 48 a quarter note (192 = one 4/4 bar); its meter
  is the pattern size in quarter notes, and where a song mixes pattern lengths the downbeats are
  the pattern starts (each column of the song starts a bar), its meter then given as `mixed`.
- Humanize and swing move the notes off the grid by design; the grid stays the truth.
"""

import fnmatch
import glob
import json
import os
import re
import struct
import sys
import xml.etree.ElementTree as ET
import zlib

HYDROGEN_SONGS = "/usr/share/hydrogen/data/demo_songs"
LMMS_PROJECTS = "/usr/share/lmms/projects"
HYDROGEN_COPYRIGHT = "/usr/share/doc/hydrogen-data/copyright"
LMMS_COPYRIGHT = "/usr/share/doc/lmms-common/copyright"

# Hydrogen and LMMS 1.2 both count 48 ticks to the quarter note (192 to a 4/4 bar).
TICKS_PER_BEAT = 48


class Excluded(Exception):
    """A project whose bar grid cannot be read without doubt; the message says why."""


def safe_name(text):
    return re.sub(r"[^A-Za-z0-9_.-]+", "-", text).strip("-")


def projects():
    """(name, kind, path) of every candidate project, sorted by name."""
    found = []
    for path in glob.glob(os.path.join(HYDROGEN_SONGS, "*.h2song")):
        base = os.path.basename(path)[: -len(".h2song")]
        found.append(("h2-" + safe_name(base), "hydrogen", path))
    for sub in ("demos", "shorties"):
        for path in glob.glob(os.path.join(LMMS_PROJECTS, sub, "**", "*.mmp*"), recursive=True):
            base = re.sub(r"\.mmpz?$", "", os.path.basename(path))
            found.append(("lmms-" + safe_name(base), "lmms", path))
    return sorted(found)


def licence(kind, path):
    """The licence Debian's copyright file gives the project (the last matching stanza wins, as
    in the machine-readable copyright format), or None."""
    if kind == "hydrogen":
        copyright_file = HYDROGEN_COPYRIGHT
        rel = "data/" + os.path.relpath(path, os.path.dirname(HYDROGEN_SONGS))
    else:
        copyright_file = LMMS_COPYRIGHT
        rel = "data/projects/" + os.path.relpath(path, LMMS_PROJECTS)
    try:
        text = open(copyright_file, encoding="utf-8").read()
    except OSError:
        return None
    found = None
    for stanza in re.split(r"\n\s*\n", text):
        match = re.search(r"^Files:(.*(?:\n[ \t].*)*)", stanza, re.M)
        lic = re.search(r"^License:\s*(\S.*)$", stanza, re.M)
        if not match or not lic:
            continue
        globs = match.group(1).split()
        if any(fnmatch.fnmatchcase(rel, g) for g in globs):
            found = lic.group(1).strip()
            copyright_text = re.search(r"^Copyright:(.*(?:\n[ \t].*)*)", stanza, re.M)
            holders = copyright_text.group(1).strip() if copyright_text else ""
            found = {"licence": found, "copyright": " ".join(holders.split()),
                     "from": copyright_file}
    return found


# ---------------------------------------------------------------------------------------------
# Hydrogen


def hydrogen_song(path):
    """bpm, meter, bar starts (ticks), first note tick, last note end tick."""
    root = ET.parse(path).getroot()
    bpm = float(root.findtext("bpm"))
    timeline = root.find("BPMTimeLine")
    if timeline is not None and len(timeline):
        raise Excluded("tempo changes (a BPM timeline)")
    if (root.findtext("isTimelineActivated") or "false") == "true":
        raise Excluded("tempo changes (the timeline is active)")
    virtual = root.find("virtualPatternList")
    if virtual is not None and len(virtual):
        raise Excluded("virtual patterns (which patterns play is not read here)")
    # A muted instrument's notes and note-off events make no sound.
    muted = {i.findtext("id") for i in root.iter("instrument") if i.findtext("isMuted") == "true"}
    patterns = {}
    for pattern in root.find("patternList"):
        size = int(pattern.findtext("size"))
        notes = []
        for note in pattern.find("noteList"):
            if note.findtext("instrument") in muted or note.findtext("note_off") == "true":
                continue
            pos = int(note.findtext("position"))
            length = int(note.findtext("length") or -1)
            if pos < size:
                notes.append((pos, pos + max(length, 0)))
        patterns[pattern.findtext("name")] = (size, notes)
    tick = 0
    bar_starts, sizes = [], set()
    first, last_end = None, None
    for group in root.find("patternSequence"):
        ids = [p.text for p in group.findall("patternID")]
        # A column lasts as long as its longest pattern (Hydrogen's rule); an empty one is a bar.
        size = max((patterns[i][0] for i in ids), default=4 * TICKS_PER_BEAT)
        if size % TICKS_PER_BEAT:
            raise Excluded(f"a pattern of {size} ticks is not a whole number of beats")
        sizes.add(size)
        bar_starts.append(tick)
        for i in ids:
            for start, end in patterns[i][1]:
                first = tick + start if first is None else min(first, tick + start)
                last_end = tick + end if last_end is None else max(last_end, tick + end)
        tick += size
    if first is None:
        raise Excluded("no notes")
    meter = f"{sizes.pop() // TICKS_PER_BEAT}/4" if len(sizes) == 1 else "mixed"
    return bpm, meter, bar_starts, tick, first, last_end


# ---------------------------------------------------------------------------------------------
# LMMS


def lmms_xml(path):
    data = open(path, "rb").read()
    if path.endswith(".mmpz"):
        # 4-byte big-endian uncompressed length, then zlib.
        (length,) = struct.unpack(">I", data[:4])
        data = zlib.decompress(data[4:])
        if len(data) != length:
            raise Excluded("the compressed project's length does not match its header")
    return ET.fromstring(data)


def lmms_song(path):
    root = lmms_xml(path)
    head = root.find("head")
    bpm_node = head.find("bpm")
    bpm = float(bpm_node.get("value") if bpm_node is not None else head.get("bpm", "140"))
    num = int(head.get("timesig_numerator", "4"))
    den = int(head.get("timesig_denominator", "4"))
    if den != 4 or num not in (2, 3, 4, 6, 12):
        raise Excluded(f"meter {num}/{den}: the bar grid is unclear")
    # Tempo automation: an automation pattern whose object is the head's bpm model.
    if bpm_node is not None and bpm_node.get("id"):
        for pattern in root.iter("automationpattern"):
            if any(o.get("id") == bpm_node.get("id") for o in pattern.findall("object")):
                raise Excluded("tempo automation")
    song = root.find("song").find("trackcontainer")
    tracks = song.findall("track")
    soloed = any(t.get("solo") == "1" for t in tracks)

    def plays(track):
        return track.get("muted") != "1" and (not soloed or track.get("solo") == "1")

    spans = []  # (start, end) in ticks of every note that sounds

    def pattern_len(pattern):
        # Projects saved before LMMS 1.2 keep no `len`: it is then LMMS's own rule, a beat
        # pattern's steps at 12 ticks each, a melody pattern's notes rounded up to whole bars.
        if pattern.get("len") is not None:
            return int(pattern.get("len"))
        if pattern.get("type") == "0":
            return int(pattern.get("steps", "16")) * 12
        end = max((int(n.get("pos")) + max(int(n.get("len")), 0)
                   for n in pattern.findall("note")), default=1)
        return max(bar, -(-end // bar) * bar)

    def pattern_notes(pattern, offset, limit):
        for note in pattern.findall("note"):
            pos = int(note.get("pos"))
            if pos < limit:
                spans.append((offset + pos, offset + pos + max(int(note.get("len")), 0)))

    # A bar is 192 ticks of 4/4 scaled by the meter (LMMS's ticksPerTact).
    bar = 4 * TICKS_PER_BEAT * num // den
    # The beat/bassline tracks, in order; the container of their instruments sits in the first.
    bb_tracks = [t for t in tracks if t.get("type") == "1"]
    bb_container = None
    for t in bb_tracks:
        c = t.find("bbtrack/trackcontainer")
        if c is not None:
            bb_container = c
    for index, track in enumerate(bb_tracks):
        if not plays(track) or bb_container is None:
            continue
        parts = []
        for inner in bb_container.findall("track"):
            if inner.get("muted") == "1" or inner.get("type") != "0":
                continue
            # Beat/bassline N plays the Nth pattern of each of its instruments (LMMS's getTCO(N)).
            patterns = inner.findall("pattern")
            if index < len(patterns) and patterns[index].get("muted") != "1":
                parts.append(patterns[index])
        # The loop is as long as its longest pattern, in whole bars (LMMS's lengthOfBB).
        loop = max([bar] + [pattern_len(p) for p in parts])
        loop = -(-loop // bar) * bar
        for tco in track.findall("bbtco"):
            if tco.get("muted") == "1":
                continue
            pos, length = int(tco.get("pos")), int(tco.get("len"))
            for start in range(0, length, loop):
                for p in parts:
                    pattern_notes(p, pos + start, min(pattern_len(p), length - start))

    for track in tracks:
        if not plays(track):
            continue
        if track.get("type") == "0":
            for pattern in track.findall("pattern"):
                if pattern.get("muted") != "1":
                    pattern_notes(pattern, int(pattern.get("pos")), pattern_len(pattern))
        elif track.get("type") == "2":
            for tco in track.findall("sampletco"):
                if tco.get("muted") != "1" and int(tco.get("len")) > 0:
                    spans.append((int(tco.get("pos")), int(tco.get("pos")) + int(tco.get("len"))))
    if not spans:
        raise Excluded("no notes")
    first = min(s for s, _ in spans)
    last_end = max(max(s, e) for s, e in spans)
    bar_starts = list(range(0, last_end + 1, bar))
    return bpm, f"{num}/{den}", bar_starts, bar_starts[-1] + bar, first, last_end


# ---------------------------------------------------------------------------------------------


def read(kind, path):
    return hydrogen_song(path) if kind == "hydrogen" else lmms_song(path)


def truth_beats(bpm, bar_starts, song_end, first, last_end):
    """(time, position) of each beat from the bar line at or before the first note to the last
    note's end."""
    start_bar = max(b for b in bar_starts if b <= first)
    bounds = bar_starts + [song_end]
    beats = []
    for bar, next_bar in zip(bounds, bounds[1:]):
        for k, tick in enumerate(range(bar, next_bar, TICKS_PER_BEAT)):
            if start_bar <= tick <= last_end:
                beats.append((tick / TICKS_PER_BEAT * 60.0 / bpm, k + 1))
    return beats


def show(path):
    """The truth of one project file, for a look or a test: `# bpm B meter M`, then the beats."""
    kind = "hydrogen" if path.endswith(".h2song") else "lmms"
    try:
        bpm, meter, bar_starts, song_end, first, last_end = read(kind, path)
    except Excluded as why:
        sys.stderr.write(f"excluded: {path}: {why}\n")
        return 1
    print(f"# bpm {bpm:g} meter {meter}")
    for time, pos in truth_beats(bpm, bar_starts, song_end, first, last_end):
        print(f"{time:.3f}\t{pos}")
    return 0


def main(argv):
    if len(argv) == 3 and argv[1] == "show":
        return show(argv[2])
    usable = len(argv) == 2 and argv[1] == "list" or len(argv) == 3 and argv[1] == "write"
    if not usable:
        sys.stderr.write("usage: beats-truth.py list | write DIR | show PROJECT\n")
        return 2
    out_dir = argv[2] if argv[1] == "write" else None
    excluded = []
    for name, kind, path in projects():
        try:
            song = read(kind, path)
        except Excluded as why:
            excluded.append((name, path, str(why)))
            continue
        except (ET.ParseError, OSError, zlib.error, ValueError, TypeError, AttributeError) as err:
            excluded.append((name, path, f"cannot read the project: {err}"))
            continue
        if out_dir is None:
            print(f"{name}\t{kind}\t{path}")
            continue
        if not os.path.exists(os.path.join(out_dir, name + ".wav")):
            continue
        bpm, meter, bar_starts, song_end, first, last_end = song
        beats = truth_beats(bpm, bar_starts, song_end, first, last_end)
        with open(os.path.join(out_dir, name + ".truth"), "w") as f:
            for time, pos in beats:
                f.write(f"{time:.3f}\t{pos}\n")
        seconds = 60.0 / bpm / TICKS_PER_BEAT
        meta = {
            "bpm": bpm,
            "meter": meter,
            "project": path,
            "renderer": "h2cli" if kind == "hydrogen" else "lmms render",
            "first_note": round(first * seconds, 3),
            "last_note_end": round(last_end * seconds, 3),
            "beats": len(beats),
            "licence": licence(kind, path),
        }
        with open(os.path.join(out_dir, name + ".json"), "w") as f:
            json.dump(meta, f, indent=1)
            f.write("\n")
    for name, _, why in excluded:
        sys.stderr.write(f"excluded: {name}: {why}\n")
    if out_dir is not None:
        with open(os.path.join(out_dir, "excluded.txt"), "w") as f:
            f.write("# NAME<TAB>PROJECT<TAB>why it is not in the benchmark\n")
            for row in excluded:
                f.write("\t".join(row) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
