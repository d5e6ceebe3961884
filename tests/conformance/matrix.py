#!/usr/bin/python3
"""The conformance matrix: every command that takes a choreography, on every robot kind, with and
without a song, given one file or a show, through the real binary and the built-in emulators.

Each cell either works, and its output is read back here by code written from the documents
(frames decoded from docs/protocol, CSV, SVG, HTML and SQLite read with Python's own libraries),
against numbers worked out from the choreography this script writes; or it refuses with the exit
status and message the documents give (EXPECTED_REFUSALS, each naming its document). A cell that
shows a fault the program still has is listed in KNOWN_FAULTS, so the test passes while it stays
visible; a known fault that starts passing fails the test until it is taken off the list.

Usage: matrix.py SEQC [--jobs N] [--no-sound]

The song cells of upload, play and show play their song (`--music`) on a sound server: a private
PulseAudio with a null sink started for the run, else the one that answers. Where there is none
(neither, or --no-sound), those cells must refuse as docs/music.md says (exit 3, no sound
server).
"""
import argparse
import base64
import concurrent.futures
import csv
import io
import math
import os
import re
import shutil
import sqlite3
import struct
import subprocess
import sys
import tempfile
import time
import wave
import xml.etree.ElementTree as ET

COMMANDS = ["check", "compile", "simulate", "plot", "preview", "export", "upload", "play", "show"]
KINDS = ["xarm", "bus", "lsc-16", "lsc-32", "lsc-6", "learm", "raspblock"]
SONGS = [False, True]
SHOWS = [False, True]

# The song: 3 s of 1 kHz clicks, one every 0.5 s from 0.5 s (120 bpm, downbeat at 0.5 s).
SONG_RATE = 22050
SONG_SECONDS = 3.0
DOWNBEAT_S = 0.5
TEMPO = 120
BEAT_MS = 60000 // TEMPO

# Each servo kind: the `robot:` name (docs/language.md, "The robot"), the emulator that speaks
# its dialect (docs/ports.md), two servos (name, wire id), where the first move puts both and
# where the second move takes the second, and the highest id of the profile (the .d6a's last
# column, docs/cli.md "seqc export"; its home is where export puts servos the file leaves).
SERVO_KINDS = {
    "xarm": dict(port="emu:xarm", a=("elbow", 4), b=("base", 6), v0=500, v1=700, home=500,
                 top_id=6, dialect="lsc"),
    "bus": dict(port="emu:xarm-hid", a=("s1", 1), b=("s3", 3), v0=500, v1=700, home=500,
                top_id=32, dialect="lsc"),
    "lsc-16": dict(port="emu:xarm", a=("ch1", 1), b=("ch15", 15), v0=1500, v1=1700, home=1500,
                   top_id=15, dialect="lsc"),
    "lsc-32": dict(port="emu:xarm-hid", a=("ch2", 2), b=("ch31", 31), v0=1500, v1=1700,
                   home=1500, top_id=31, dialect="lsc"),
    "lsc-6": dict(port="emu:lsc6", a=("ch1", 1), b=("ch3", 3), v0=1500, v1=1700, home=1500,
                  top_id=6, dialect="lsc6"),
    "learm": dict(port="emu:lsc6", a=("elbow", 4), b=("base", 6), v0=1500, v1=1700, home=1500,
                  top_id=6, dialect="lsc6"),
}
CAR_PORT = "emu:raspblock"
# Two performers of the same kind in every show; a servo controller stores each in its group.
PERFORMERS = [("lead", 0), ("echo", 2)]

# What each servo-kind choreography must compile to: the first step moves both servos to v0 over
# 1000 ms (2 beats at 120 bpm with the song), the second the second servo to v1 over 1000 ms.
MOVE_MS = 1000


def servo_actions(k):
    s = SERVO_KINDS[k]
    return [(MOVE_MS, {s["a"][1]: s["v0"], s["b"][1]: s["v0"]}), (MOVE_MS, {s["b"][1]: s["v1"]})]


# The car (docs/raspblock.md): `move: home` over 500 ms goes straight to 1500/1500 at 0 ("an
# output with no known position yet goes straight to its target at the start"); pan 1500->1700
# over 1000 ms in 2 steps sends 1600 at 500 and 1700 at 1000 ("step k of n carries the position
# k/n of the way and is sent at (k-1)/n of the time"); `drive: {y: 10}` for 500 ms from 1500, then
# the stream's closing stop (all zero) at 2000.
CAR_PACKETS = [
    (0, ("gimbal", 1500, 1500)),
    (500, ("gimbal", 1600, 1500)),
    (1000, ("gimbal", 1700, 1500)),
    (1500, ("rocker", 0, 10, 0)),
    (2000, ("rocker", 0, 0, 0)),
]

# Refusals the documents promise, first match wins: (command, kinds or None for every kind,
# song or None, show or None, needs a sound server or None) -> (exit status, message fragment).
EXPECTED_REFUSALS = [
    # docs/language.md, "Diagnostics": a show file given to compile, simulate or export says it is
    # a show and that `seqc show FILE` runs it (an error, so exit 1 by docs/cli.md's table).
    # simulate is left out: docs/cli.md ("Given a show file, simulate gives one CSV per
    # performer") and the program agree that it works.
    (("compile", None, None, True, None), (1, "this is a show file")),
    (("export", None, None, True, None), (1, "this is a show file")),
    # The same located error for the two device commands that take one choreography
    # (docs/cli.md: `seqc upload FILE`, `seqc play FILE`; a show runs with `seqc show`).
    (("upload", None, None, True, None), (1, "this is a show file")),
    (("play", None, None, True, None), (1, "this is a show file")),
    # docs/cli.md, "seqc show SHOW.yaml": the argument is a show file; a choreography is invalid
    # input for it (exit 1), each of its keys an unknown key of a show file.
    (("show", None, None, False, None), (1, "in a show file")),
    # docs/raspblock.md: "There is no upload: `seqc upload` on a Raspblock file explains this and
    # points to `play`" (the board has no storage, README.md).
    (("upload", ["raspblock"], None, False, None), (1, "which has no storage")),
    # docs/raspblock.md: the board stores nothing, a car program is a timed packet stream; a .d6a
    # holds one row of servo positions per controller action (docs/d6a.md).
    (("export", ["raspblock"], None, False, None), (1, "a Raspblock program is a live stream")),
    # docs/music.md, "Playing the song with the robot": without a sound server seqc says so and
    # sends nothing (exit 3, as for a port that is not there; also docs/cli.md's table).
    (("upload", None, True, False, False), (3, "cannot connect to the sound server")),
    (("play", None, True, False, False), (3, "cannot connect to the sound server")),
    (("show", None, True, True, False), (3, "cannot connect to the sound server")),
]

# Cells that show a fault of the program (or of its documents) today: (command, kind, song,
# show) -> (what its failure says, why it is a fault). Each must still fail, and for that reason;
# the table's report prints them.
KNOWN_FAULTS = {}


class CellFailure(Exception):
    pass


def expect(cond, what):
    if not cond:
        raise CellFailure(what)


def expected_refusal(command, kind, song, show, sound):
    for (c, kinds, s, sh, snd), outcome in EXPECTED_REFUSALS:
        if c != command or (kinds is not None and kind not in kinds):
            continue
        if (s is not None and s != song) or (sh is not None and sh != show):
            continue
        if snd is not None and snd != sound:
            continue
        return outcome
    return None


# ---------------------------------------------------------------------------------------------
# The files the cells run on.

def write_song(path):
    n = int(SONG_RATE * SONG_SECONDS)
    samples = [0] * n
    t = DOWNBEAT_S
    while t < SONG_SECONDS:
        start = int(t * SONG_RATE)
        for i in range(int(0.03 * SONG_RATE)):
            if start + i < n:
                env = math.exp(-i / (0.005 * SONG_RATE))
                samples[start + i] = int(20000 * env * math.sin(2 * math.pi * 1000 * i / SONG_RATE))
        t += BEAT_MS / 1000
    with wave.open(path, "wb") as w:
        w.setnchannels(1)
        w.setsampwidth(2)
        w.setframerate(SONG_RATE)
        w.writeframes(b"".join(struct.pack("<h", v) for v in samples))


def music_block(song):
    if not song:
        return ""
    return (f"music:\n  file: song.wav\n  downbeat: {DOWNBEAT_S}s\n  tempo: {TEMPO}\n"
            "  meter: 4/4\n")


def ms_or_beats(ms, song):
    return f"{ms // BEAT_MS}b" if song else f"{ms}ms"


def choreography(kind, song):
    if kind == "raspblock":
        return (f"robot: raspblock\n{music_block(song)}sequence:\n"
                f"  - move: home\n    time: {ms_or_beats(500, song)}\n"
                f"  - move: {{pan: 1700, tilt: 1500}}\n    time: {ms_or_beats(1000, song)}\n"
                "    steps: 2\n"
                f"  - drive: {{y: 10}}\n    time: {ms_or_beats(500, song)}\n")
    s = SERVO_KINDS[kind]
    a, b = s["a"][0], s["b"][0]
    step = ms_or_beats(MOVE_MS, song)
    return (f"robot: {kind}\n{music_block(song)}sequence:\n"
            f"  - move: {{{a}: {s['v0']}, {b}: {s['v0']}}}\n    time: {step}\n"
            f"  - move: {{{b}: {s['v1']}}}\n    time: {step}\n")


def port_of(kind):
    return CAR_PORT if kind == "raspblock" else SERVO_KINDS[kind]["port"]


def file_name(kind, song):
    return f"{kind}{'-song' if song else ''}.yaml"


def show_name(kind, song):
    return f"show-{kind}{'-song' if song else ''}.yaml"


def write_files(tmp):
    write_song(os.path.join(tmp, "song.wav"))
    for kind in KINDS:
        for song in SONGS:
            with open(os.path.join(tmp, file_name(kind, song)), "w") as f:
                f.write(choreography(kind, song))
            lines = [f"show: {kind}-show", "performers:"]
            for name, group in PERFORMERS:
                g = "" if kind == "raspblock" else f", group: {group}"
                solo = file_name(kind, song)
                lines.append(f"  {name}: {{file: {solo}, port: {port_of(kind)}{g}}}")
            with open(os.path.join(tmp, show_name(kind, song)), "w") as f:
                f.write("\n".join(lines) + "\n")


# ---------------------------------------------------------------------------------------------
# Readers written from the documents.

def parse_hex(text):
    return bytes(int(x, 16) for x in text.split())


def lsc_frames(data):
    """Servo controller frames (docs/protocol/servo-controller.md, lsc-6.md): 55 55 LEN CMD DATA,
    LEN = len(DATA) + 2. Returns [(offset, cmd, data)]; raises on bytes between frames."""
    out, i = [], 0
    while i < len(data):
        expect(data[i:i + 2] == b"\x55\x55", f"bytes between frames at {i}: {data[i:i+8].hex(' ')}")
        expect(i + 4 <= len(data), "a frame cut short")
        length = data[i + 2]
        expect(length >= 2 and i + 2 + length <= len(data), f"a frame cut short at {i}")
        out.append((i, data[i + 3], data[i + 4:i + 2 + length]))
        i += 2 + length
    return out


def u16le(b, i):
    return b[i] | (b[i + 1] << 8)


def servo_list(data, i, count):
    targets = {}
    for k in range(count):
        sid = data[i + 3 * k]
        expect(sid not in targets, f"servo {sid} twice in one action")
        targets[sid] = u16le(data, i + 3 * k + 1)
    return targets


def group_download_actions(frames, group):
    """GroupDownload (CMD 5) step 4 frames: 04 G b i 0B tLo tHi {id posLo posHi}... Checks the
    step order 1, 2, 3, 4..., 5 and the counts; returns [(time, {id: pos})]."""
    steps = [(d[0], d) for _, cmd, d in frames if cmd == 5]
    expect(steps, "no GroupDownload frames")
    expect([s for s, _ in steps][:3] == [1, 2, 3] and steps[-1][0] == 5,
           f"steps out of order: {[s for s, _ in steps]}")
    actions = []
    for step, d in steps:
        expect(d[1] == group, f"step {step} for group {d[1]}, expected {group}")
        if step == 4:
            block, index, marker = d[2], d[3], d[4]
            expect(marker == 0x0B, f"action marker {marker:#x}")
            expect(block * 255 + index == len(actions), f"action slot {block}/{index} out of order")
            # The servo count is the one byte the servo-controller document's table leaves implicit:
            # it is what is left after the time, three bytes a servo.
            rest = d[7:]
            expect(len(rest) % 3 == 0, "a servo list that is not three bytes a servo")
            actions.append((u16le(d, 5), servo_list(rest, 0, len(rest) // 3)))
    opened = [d for s, d in steps if s == 1][0]
    expect(sum(opened[2:]) == len(actions), f"step 1 announces {sum(opened[2:])} actions")
    return actions


def lsc6_download_actions(frames, group):
    """LSC-6 DownloadAction (CMD 25): G TOTAL IDX N tLo tHi {id pLo pHi}xN (docs/protocol/
    lsc-6.md). Returns [(time, {id: pos})] in index order, re-sends collapsed."""
    slots = {}
    total = None
    for _, cmd, d in frames:
        if cmd != 0x19:
            continue
        expect(d[0] == group, f"DownloadAction for group {d[0]}, expected {group}")
        total = d[1] if total is None else total
        expect(d[1] == total, "TOTAL changes between actions")
        n = d[3]
        expect(len(d) == 6 + 3 * n, f"DownloadAction LEN does not match its {n} servos")
        slots[d[2]] = (u16le(d, 4), servo_list(d, 6, n))
    expect(total is not None, "no DownloadAction frames")
    expect(sorted(slots) == list(range(total)), f"indexes {sorted(slots)} of {total}")
    return [slots[i] for i in range(total)]


def moves_of(frames):
    """MultiServoMove / the LSC-6 Move (CMD 3): N tLo tHi {id pLo pHi}xN."""
    out = []
    for off, cmd, d in frames:
        if cmd == 3:
            expect(len(d) == 3 + 3 * d[0], "a move's LEN does not match its servo count")
            out.append((off, u16le(d, 1), servo_list(d, 3, d[0])))
    return out


def car_packets(data):
    """Raspblock packets (docs/protocol/raspblock.md): FF FE FUNC LEN DATA CHK, CHK = (FUNC +
    LEN + sum(DATA)) & 0xFF, 16-bit values big-endian. Returns [(offset, decoded)]."""
    out, i = [], 0
    while i < len(data):
        expect(data[i:i + 2] == b"\xff\xfe", f"bytes between packets at {i}")
        func, length = data[i + 2], data[i + 3]
        body = data[i + 4:i + 4 + length]
        expect(len(body) == length and i + 4 + length < len(data), "a packet cut short")
        chk = data[i + 4 + length]
        expect(chk == (func + length + sum(body)) & 0xFF, f"bad checksum at {i}")
        if func == 2 and length == 4:
            dec = ("gimbal", (body[0] << 8) | body[1], (body[2] << 8) | body[3])
        elif func == 3 and length == 8:
            expect(body[0] == 1, "rocker mode byte is not 01")
            x, y, z, direction = ((body[1] << 8) | body[2], (body[3] << 8) | body[4],
                                  (body[5] << 8) | body[6], body[7])
            # Signs in the direction byte: bit 2 X < 0, bit 1 Y < 0, bit 0 set when Z >= 0.
            x = -x if direction & 4 else x
            y = -y if direction & 2 else y
            z = z if direction & 1 else -z
            dec = ("rocker", x, y, z)
        else:
            dec = ("func", func, body.hex(" "))
        out.append((i, dec))
        i += 5 + length
    return out


def read_trace(path):
    """A --trace file (docs/trace.md): `t=SECONDS > hex` lines are one write each. Returns the
    bytes written, each write's (offset, t) and the header lines."""
    sent, starts, header = bytearray(), [], []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                header.append(line)
                continue
            m = re.match(r"t=(\d+\.\d+) > ([0-9a-f ]+)$", line.strip())
            if m:
                starts.append((len(sent), float(m.group(1))))
                sent += parse_hex(m.group(2))
    return bytes(sent), starts, header


def time_at(starts, offset):
    best = None
    for off, t in starts:
        if off <= offset:
            best = t
    return best


# ---------------------------------------------------------------------------------------------
# The cells.

class Runner:
    def __init__(self, seqc, tmp, sound):
        self.seqc, self.tmp, self.sound = seqc, tmp, sound
        with open(os.path.join(tmp, "song.wav"), "rb") as f:
            self.song_b64 = base64.b64encode(f.read()).decode()

    def run(self, *args, timeout=60):
        return subprocess.run([self.seqc, *args], capture_output=True, text=True, cwd=self.tmp,
                              timeout=timeout)

    def path(self, name):
        return os.path.join(self.tmp, name)

    def cell(self, command, kind, song, show):
        """Runs one cell and returns "ok" or "refuses(N)"; raises CellFailure."""
        tag = f"{command}-{kind}-{'song' if song else 'quiet'}-{'show' if show else 'file'}"
        target = show_name(kind, song) if show else file_name(kind, song)
        args, outputs = self.arguments(command, kind, song, show, target, tag)
        r = self.run(*args)
        refusal = expected_refusal(command, kind, song, show, self.sound)
        if refusal is not None:
            code, fragment = refusal
            expect(r.returncode == code and fragment in r.stderr,
                   f"expected exit {code} with '{fragment}', got {r.returncode}: "
                   f"{r.stderr.strip()[-300:]}")
            # A refusal writes no output and sends nothing ("an invalid file sends nothing and
            # never opens the port", docs/cli.md; "nothing was sent", docs/music.md).
            for out in outputs:
                if out.endswith(".trace"):
                    expect(not os.path.exists(out) or read_trace(out)[0] == b"",
                           f"a refused {command} sent bytes ({out})")
                else:
                    expect(not os.path.exists(out), f"{out} written by a refused command")
            return f"refuses({code})"
        expect(r.returncode == 0, f"exit {r.returncode}: {r.stderr.strip()[-400:]}")
        getattr(self, "verify_" + command)(kind, song, show, r, tag)
        return "ok"

    def arguments(self, command, kind, song, show, target, tag):
        if command == "check":
            return [command, target], []
        if command in ("compile", "plot", "preview", "export", "simulate"):
            ext = {"compile": "hex", "plot": "svg", "preview": "html", "export": "d6a",
                   "simulate": "csv"}[command]
            out = self.path(f"{tag}.{ext}")
            extra = {"compile": ["--emit", "hex"], "simulate": ["--step", "500"]}.get(command, [])
            return [command, target, "-o", out, *extra], [out]
        music = ["--music"] if song else []
        trace = self.path(f"{tag}.trace")
        if command == "upload":
            return [command, target, "--port", port_of(kind), "--run", "--trace", trace,
                    *music], [trace]
        if command == "play":
            return [command, target, "--port", port_of(kind), "--trace", trace, *music], [trace]
        # docs/trace.md: `seqc show --trace PREFIX` writes PREFIX-NAME.trace per performer.
        return [command, target, "--trace", self.path(tag), *music], \
            [self.path(f"{tag}-{name}.trace") for name, _ in PERFORMERS]

    # ----- offline commands

    def verify_check(self, kind, song, show, r, tag):
        lines = r.stdout.splitlines()
        files = [file_name(kind, song)] * (2 if show else 1)
        if show:
            expect(lines[0] == f"{show_name(kind, song)}: show with 2 performers", lines[0])
            lines = lines[1:]
        expect(len(lines) == len(files), f"summary lines: {r.stdout}")
        for line in lines:
            # docs/cli.md, seqc check: the group's budget, or `ok (N packets, D s)` for a stream.
            # The LSC-6 stores at most 255 actions a group (docs/protocol/lsc-6.md, Limits).
            budget = 255 if kind in ("lsc-6", "learm") else 1020
            want = ("ok (5 packets, 2 s)" if kind == "raspblock"
                    else f"2/{budget} actions, 2.000 s, fit within 0 units")
            expect(want in line, f"summary '{line}', expected '{want}'")

    def verify_compile(self, kind, song, show, r, tag):
        with open(self.path(f"{tag}.hex")) as f:
            text = f.read()
        if kind == "raspblock":
            # docs/raspblock.md: the send time in ms, then the frame.
            got = []
            for line in text.splitlines():
                m = re.match(r"\s*(\d+) ms\s+([0-9a-f ]+)$", line)
                expect(m, f"line '{line}'")
                got += [(int(m.group(1)), p) for _, p in car_packets(parse_hex(m.group(2)))]
            expect(got == CAR_PACKETS, f"packets {got}")
            return
        frames = lsc_frames(parse_hex(text))
        s = SERVO_KINDS[kind]
        if s["dialect"] == "lsc6":
            actions = lsc6_download_actions(frames, 0)
        else:
            actions = group_download_actions(frames, 0)
        expect(actions == servo_actions(kind), f"actions {actions}")

    def verify_simulate(self, kind, song, show, r, tag):
        # docs/cli.md: given a show, with -o OUT.csv each performer's CSV goes to OUT-NAME.csv.
        names = [f"{tag}-{name}.csv" for name, _ in PERFORMERS] if show else [f"{tag}.csv"]
        tables = []
        for name in names:
            expect(os.path.exists(self.path(name)), f"no {name}")
            with open(self.path(name)) as f:
                tables.append(f.read())
        for table in tables:
            rows = {int(row["time_ms"]): row for row in csv.DictReader(io.StringIO(table))}
            expect(sorted(rows) == [0, 500, 1000, 1500, 2000], f"times {sorted(rows)}")
            if kind == "raspblock":
                # docs/cli.md: each field is what the packets sent so far set.
                for t, pan, y in [(0, 1500, 0), (500, 1600, 0), (1000, 1700, 0), (1500, 1700, 10),
                                  (2000, 1700, 0)]:
                    expect(int(rows[t]["pan"]) == pan and int(rows[t]["y"]) == y,
                           f"at {t} ms: {rows[t]}")
                continue
            s = SERVO_KINDS[kind]
            a, b = s["a"][0], s["b"][0]
            # Each action moves its servos in a straight line from where they are over its time,
            # from home: v0 held from 0 (home = v0), then b from v0 to v1 over 1000..2000 ms.
            for t in [0, 500, 1000, 1500, 2000]:
                want_b = s["v0"] + (s["v1"] - s["v0"]) * max(0, t - 1000) / 1000
                expect(float(rows[t][a]) == s["v0"] and float(rows[t][b]) == want_b,
                       f"at {t} ms: {a}={rows[t][a]} {b}={rows[t][b]}, expected {want_b}")

    def verify_plot(self, kind, song, show, r, tag):
        root = ET.parse(self.path(f"{tag}.svg")).getroot()
        expect(root.tag.endswith("svg"), f"root element {root.tag}")
        texts = {"".join(e.itertext()).strip() for e in root.iter() if e.tag.endswith("text")}
        names = ["pan", "tilt"] if kind == "raspblock" else [SERVO_KINDS[kind]["a"][0],
                                                              SERVO_KINDS[kind]["b"][0]]
        for n in names:
            expect(n in texts, f"no lane named {n}")
        if show:
            joined = " ".join(texts)
            for name, _ in PERFORMERS:
                expect(name in joined, f"performer {name} not named")
        song_lane = any(e.get("class") == "song" for e in root.iter())
        expect(song_lane == song, f"song lane {'missing' if song else 'drawn without a song'}")

    def verify_preview(self, kind, song, show, r, tag):
        with open(self.path(f"{tag}.html")) as f:
            page = f.read()
        expect(page.lstrip().lower().startswith("<!doctype html"), "not an HTML page")
        expect("http://" not in page and "https://" not in page, "the page names a URL")
        names = ["pan", "tilt"] if kind == "raspblock" else [SERVO_KINDS[kind]["a"][0],
                                                              SERVO_KINDS[kind]["b"][0]]
        for n in names:
            expect(n in page, f"servo {n} not in the page")
        # docs/preview.md: the audio file's own bytes embedded as a data: URL.
        audio = re.search(r'<audio id="song"[^>]*src="data:audio/wav;base64,([A-Za-z0-9+/=]*)"',
                          page)
        if song:
            expect(audio is not None, "no <audio id=\"song\"> with the song")
            expect(audio.group(1) == self.song_b64, "the embedded audio is not the song's bytes")
        else:
            expect(audio is None and 'id="song"' not in page, "a song in a page without one")

    def verify_export(self, kind, song, show, r, tag):
        s = SERVO_KINDS[kind]
        db = sqlite3.connect(self.path(f"{tag}.d6a"))
        try:
            cols = [row[1] for row in db.execute("pragma table_info(ActionGroup)")]
            want_cols = ["Index", "Time"] + [f"Servo{i}" for i in range(1, s["top_id"] + 1)]
            expect(cols == want_cols, f"columns {cols}")
            rows = list(db.execute("select * from ActionGroup order by [Index]"))
        finally:
            db.close()
        # docs/cli.md: every servo at its position at the end of that action; servos the file
        # never moves stay at home.
        pos = {i: s["home"] for i in range(1, s["top_id"] + 1)}
        want = []
        for index, (ms, targets) in enumerate(servo_actions(kind), 1):
            pos.update(targets)
            want.append((index, ms, *[pos[i] for i in range(1, s["top_id"] + 1)]))
        expect(rows == want, f"rows {rows}, expected {want}")

    # ----- device commands

    def check_run_decode(self, trace):
        # `seqc decode` as a convenience: a trace of a clean run has no issue.
        r = self.run("decode", trace)
        expect(r.returncode == 0, f"seqc decode {trace}: exit {r.returncode} {r.stderr.strip()}")

    def check_times(self, starts, song):
        # In emulated time, every write of a run this short happens within the song (or a few
        # seconds without one) of the trace's start (docs/trace.md: seconds since it began).
        limit = SONG_SECONDS + 2 if song else 5
        last = max(t for _, t in starts)
        expect(last < limit, f"a write at t={last:.3f} s in the trace (over {limit} s)")

    def verify_stored(self, kind, trace, group, song):
        sent, starts, _ = read_trace(trace)
        frames = lsc_frames(sent)
        s = SERVO_KINDS[kind]
        if s["dialect"] == "lsc6":
            actions = lsc6_download_actions(frames, group)
            # docs/protocol/lsc-6.md: an upload must never send erase (CMD 8), which wipes
            # every group on the board.
            expect(all(cmd != 8 for _, cmd, _ in frames), "the upload sent an erase")
        else:
            actions = group_download_actions(frames, group)
        run_cmd = 6
        expect(actions == servo_actions(kind), f"stored actions {actions}")
        # GroupRun / Run: G, times 1 (docs/protocol), after the last action frame.
        runs = [(off, d) for off, cmd, d in frames if cmd == run_cmd]
        expect(len(runs) == 1 and runs[0][1] == bytes([group, 1, 0]), f"run frames {runs}")
        last_action = max(off for off, cmd, _ in frames if cmd in (5, 0x19))
        expect(runs[0][0] > last_action, "the group was run before it was stored")
        # Every servo kind runs here on an in-process emulator, in emulated time.
        self.check_times(starts, song)
        self.check_run_decode(trace)

    def verify_streamed(self, kind, trace, song):
        sent, starts, _ = read_trace(trace)
        if kind == "raspblock":
            packets = car_packets(sent)
            got = [p for _, p in packets]
            expect(got == [p for _, p in CAR_PACKETS], f"packets {got}")
            # The car's emulator keeps the host's time, which no test holds to a threshold
            # (docs/architecture.md, Tests): the packets only go out in their order.
            times = [time_at(starts, off) for off, _ in packets]
            expect(times == sorted(times), f"packets written out of order: {times}")
        else:
            frames = lsc_frames(sent)
            moves = moves_of(frames)
            if SERVO_KINDS[kind]["dialect"] == "lsc6":
                # docs/commands.md, "A file for the other board": one GetBatteryVoltage (55 55
                # 02 0f), which the LSC-6 ignores, precedes its moves; nothing else does.
                expect([cmd for _, cmd, _ in frames if cmd != 3] == [0x0F]
                       and frames[0][1] == 0x0F, "frames other than the question and moves")
            got = [(ms, targets) for _, ms, targets in moves]
            # docs/commands.md, Live play: one move per step, the first with every servo it
            # names, then only the servos whose target changes.
            expect(got == servo_actions(kind), f"moves {got}")
            # The in-process emulators keep emulated time, exact to the nanosecond. Each move is
            # timed to finish arriving at its step (docs/commands.md, Live play): its write time
            # plus its own bytes (55 55 LEN CMD + data) x 10 bits / 9600 baud, one step apart.
            # Over USB HID a report goes out whole on the polling interval: no wire time.
            per_byte = 0 if "hid" in SERVO_KINDS[kind]["port"] else 10 / 9600
            arrive = [time_at(starts, off) + (4 + 3 + 3 * len(targets)) * per_byte
                      for off, _, targets in moves]
            t0, t1 = arrive
            expect(abs((t1 - t0) * 1000 - MOVE_MS) < 0.01,
                   f"moves arrive {(t1 - t0) * 1000:.3f} ms apart")
            self.check_times(starts, song)
        self.check_run_decode(trace)

    def verify_upload(self, kind, song, show, r, tag):
        self.verify_stored(kind, self.path(f"{tag}.trace"), 0, song)
        expect("acknowledged 2 actions into group 0" in r.stderr, r.stderr.strip()[-300:])

    def verify_play(self, kind, song, show, r, tag):
        self.verify_streamed(kind, self.path(f"{tag}.trace"), song)

    def verify_show(self, kind, song, show, r, tag):
        for name, group in PERFORMERS:
            trace = self.path(f"{tag}-{name}.trace")
            if kind == "raspblock":
                self.verify_streamed(kind, trace, song)
            else:
                self.verify_stored(kind, trace, group, song)


def sound_server_answers():
    try:
        return subprocess.run(["pactl", "info"], capture_output=True, timeout=10).returncode == 0
    except (OSError, subprocess.TimeoutExpired):
        return False


def start_private_pulse(folder):
    """Where PulseAudio is installed, starts a server with a null sink on a socket in `folder` for
    this run (as tests/music/with_pulse.sh does, at normal priority) and points every seqc
    started here at it. Returns the server's process, or None (then whatever server answers, if
    any, is used)."""
    if not shutil.which("pulseaudio") or not shutil.which("pactl"):
        return None
    saved = dict(os.environ)
    os.environ.update(XDG_RUNTIME_DIR=folder, HOME=folder)
    server = subprocess.Popen(
        ["pulseaudio", "--daemonize=no", "--exit-idle-time=-1", "--system=false", "-n",
         "--use-pid-file=no", "--log-target=stderr", "--log-level=error",
         "--load=module-null-sink sink_name=seqc_null rate=44100 norewinds=1",
         f"--load=module-native-protocol-unix socket={folder}/native auth-anonymous=1"],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    os.environ["PULSE_SERVER"] = f"unix:{folder}/native"
    # Waits for the server to answer (or to end), not for a fixed time.
    while server.poll() is None and not sound_server_answers():
        time.sleep(0.05)
    if server.poll() is not None:
        os.environ.clear()
        os.environ.update(saved)
        return None
    subprocess.run(["pactl", "set-default-sink", "seqc_null"], capture_output=True, timeout=10)
    return server


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("seqc")
    ap.add_argument("--jobs", type=int, default=4)
    ap.add_argument("--no-sound", action="store_true",
                    help="start no sound server: the song cells of upload, play and show refuse")
    args = ap.parse_args()
    seqc = os.path.abspath(args.seqc)
    with tempfile.TemporaryDirectory(prefix="seqc-matrix-pulse-") as folder:
        # A private server even when the desk's answers, so the clicks play into a null sink.
        server = None if args.no_sound else start_private_pulse(folder)
        try:
            return run_matrix(seqc, args.jobs, not args.no_sound and sound_server_answers())
        finally:
            if server is not None:
                server.terminate()
                server.wait()


def run_matrix(seqc, jobs, sound):
    begun = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="seqc-matrix-") as tmp:
        write_files(tmp)
        runner = Runner(seqc, tmp, sound)
        cells = [(c, k, s, sh) for c in COMMANDS for k in KINDS for s in SONGS for sh in SHOWS]

        def one(cell):
            try:
                return cell, runner.cell(*cell), ""
            except CellFailure as e:
                return cell, "FAIL", str(e)
            except subprocess.TimeoutExpired as e:
                return cell, "FAIL", f"timed out: {e}"
            except Exception as e:  # a reader that met what it did not expect: the cell fails
                return cell, "FAIL", f"{type(e).__name__}: {e}"

        # The real-time cells (songs, the car) mostly wait, so they run side by side.
        with concurrent.futures.ThreadPoolExecutor(jobs) as pool:
            results = {cell: (outcome, why) for cell, outcome, why in pool.map(one, cells)}
    elapsed = time.monotonic() - begun

    problems = []
    shown = {}
    counts = {"ok": 0, "refuses": 0, "known fault": 0}
    for cell, (outcome, why) in results.items():
        # Without a sound server the song cells refuse before the fault could show.
        known = KNOWN_FAULTS.get(cell) if expected_refusal(*cell, sound) is None else None
        if known is not None:
            if outcome == "FAIL" and known[0] in why:
                shown[cell] = "known"
                counts["known fault"] += 1
            elif outcome == "FAIL":
                shown[cell] = "FAIL"
                problems.append(f"{cell}: {why} (a known fault, but it fails otherwise)")
            else:
                shown[cell] = "FIXED?"
                problems.append(f"{cell}: listed in KNOWN_FAULTS but it passes ({outcome}): "
                                "take it off the list")
            continue
        shown[cell] = outcome
        if outcome == "FAIL":
            problems.append(f"{cell}: {why}")
        else:
            counts["refuses" if outcome.startswith("refuses") else "ok"] += 1

    # One block per song x show, so each line stays readable: rows are commands, columns kinds.
    width = 11
    print(f"conformance matrix (sound server: {'yes' if sound else 'no'})")
    for s in SONGS:
        for sh in SHOWS:
            print(f"\n{'a song' if s else 'no song'}, {'a show' if sh else 'one file'}:")
            print(" " * 9 + "".join(f"{k:<{width}}" for k in KINDS))
            for c in COMMANDS:
                print(f"{c:<9}" + "".join(f"{shown[(c, k, s, sh)]:<{width}}" for k in KINDS))
    total = len(results)
    print(f"{total} cells: {counts['ok']} ok, {counts['refuses']} refuse as documented, "
          f"{counts['known fault']} known faults, {len(problems)} failures; {elapsed:.1f} s")
    for cell, (_, why) in KNOWN_FAULTS.items():
        if shown.get(cell) == "known":
            print(f"known fault {cell}: {why}\n    seen: {results[cell][1]}")
    for p in problems:
        print(f"FAIL {p}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
