#!/usr/bin/env python3
"""`seqc follow --fpp` end to end: a MultiSync master written here from FPP's
docs/ControlProtocol.txt (docs/protocol/fpp-multisync.md) sends open, start, syncs and stop of
show.fseq to 127.0.0.1:<a free port>, where seqc listens (--listen).

The arm: walk-joints.yaml on the in-process emu:xarm. The group is stored on open, started on
start (seqc's "started group 0" line, timed here as it arrives, must come within 25 ms, one FSEQ
frame, of the master's start), a discovery ping is answered as a remote, a sync of another file
is ignored, stop stops it.

The car: car-dance.yaml on `seqc emulate raspblock`'s pseudo-terminal, whose state changes are
timed here as they arrive on its stderr (its own clock is tied to ours by the smallest difference
seen). The first change must come within 25 ms of the master's start; each gimbal change must
arrive when the master's clock says its frame is due; a sync 3.2 s in that jumps 10 s ahead
must bring the car's first change of the new place within 25 ms; a stop 6 s in (dance 16 s)
must leave the frames after 16 s unsent. Prints the start skew and the steady-state error
(median, p99) of each.

Usage: multisync_test.py SEQC SOURCE_DIR
"""
import json
import os
import re
import socket
import struct
import subprocess
import sys
import threading
import time

FRAME_S = 0.025  # one FSEQ frame at 40 fps


def fail(message):
    print("multisync_test: " + message, file=sys.stderr)
    sys.exit(1)


# The layout of docs/protocol/fpp-multisync.md: "FPPD", type, extra length (LE), then for a sync
# packet action (0 start, 1 stop, 2 sync, 3 open), file type (0 sequence, 1 media), frame (u32
# LE), seconds elapsed (float LE), the file name and its NUL.
def sync_packet(action, name, seconds=0.0, frame=0, file_type=0):
    data = struct.pack("<BBIf", action, file_type, frame, seconds) + name.encode() + b"\0"
    return b"FPPD" + bytes([1]) + struct.pack("<H", len(data)) + data


def discover_packet():
    extra = bytearray(294)
    extra[0] = 3       # ping version
    extra[1] = 1       # discover
    extra[2] = 0x13    # a Pi 4 running FPP
    extra[7] = 0x02 | 0x04  # player, sending MultiSync
    extra[8:12] = bytes([127, 0, 0, 1])
    extra[12:18] = b"master"
    return b"FPPD" + bytes([4]) + struct.pack("<H", len(extra)) + bytes(extra)


START, STOP, SYNC, OPEN = 0, 1, 2, 3


def free_port():
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Lines:
    """A process's stderr, each line with the instant it arrived."""

    def __init__(self, stream):
        self.lines = []
        self.thread = threading.Thread(target=self._read, args=(stream,), daemon=True)
        self.thread.start()

    def _read(self, stream):
        for line in iter(stream.readline, ""):
            self.lines.append((time.monotonic(), line.rstrip("\n")))

    def wait_for(self, text, timeout=10):
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            for t, line in list(self.lines):
                if text in line:
                    return t, line
            time.sleep(0.005)
        fail("never saw %r in:\n%s" % (text, "\n".join(l for _, l in self.lines)))


def percentile(values, q):
    v = sorted(abs(x) for x in values)
    if not v:
        return 0.0
    k = max(1, int(-(-q * len(v) // 1)))
    return v[min(k, len(v)) - 1]


def start_follow(seqc, source, dance, port, listen):
    proc = subprocess.Popen([seqc, "follow", dance, "--fpp", "show", "--port", port, "--listen",
                             listen, "--once"], cwd=source, stderr=subprocess.PIPE, text=True,
                            bufsize=1)
    lines = Lines(proc.stderr)
    lines.wait_for("seqc: following show")
    return proc, lines


def arm(seqc, source):
    udp = free_port()
    proc, lines = start_follow(seqc, source, "tests/data/walk-joints.yaml", "emu:xarm",
                               "127.0.0.1:%d" % udp)
    master = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    master.bind(("127.0.0.1", 0))
    master.settimeout(2)
    to = ("127.0.0.1", udp)
    master.sendto(discover_packet(), to)
    answer, _ = master.recvfrom(2048)
    remote = answer[:7] == b"FPPD\x04" + struct.pack("<H", 294)
    if not remote or answer[9] != 0xC0 or answer[14] != 0x08:
        fail("the ping answer is not a remote's: %s" % answer[:20].hex(" "))
    master.sendto(sync_packet(OPEN, "show.fseq"), to)
    lines.wait_for("stored")
    time.sleep(0.2)
    t0 = time.monotonic()
    master.sendto(sync_packet(START, "show.fseq"), to)
    started, said = lines.wait_for("started group 0")
    while time.monotonic() - t0 < 2.0:
        time.sleep(0.25)
        e = time.monotonic() - t0
        master.sendto(sync_packet(SYNC, "show.fseq", e, int(e / FRAME_S)), to)
    master.sendto(sync_packet(SYNC, "other.fseq", 50.0, 2000), to)  # another file: ignored
    master.sendto(sync_packet(STOP, "show.fseq"), to)
    code = proc.wait(timeout=10)
    text = "\n".join(l for _, l in lines.lines)
    if code != 0:
        fail("follow (arm) exited %d:\n%s" % (code, text))
    for want in ("stored 27 actions in group 0", "1 about other files", "(1 answered)",
                 "sent the stop", "0 correction(s)"):
        if want not in text:
            fail("follow (arm) did not say %r:\n%s" % (want, text))
    # Written `late` after its time, which is the master's start less the start's wire time: so
    # its last byte reached the board `late` after the master's start (seqc heard the start
    # `heard` after it was sent).
    late = float(re.search(r"\(([\d.]+) ms after its time\)", said).group(1)) / 1e3
    heard = started - t0
    if late > FRAME_S or heard > FRAME_S:
        fail("the arm started %.1f ms after the master (more than one frame)" % (late * 1e3))
    m = re.search(r"median ([\d.]+) ms, p99 ([\d.]+) ms", text)
    print("arm: start skew %.1f ms (the GroupRun's last byte in; written %.1f ms after the "
          "master's start); steady-state offset median %s ms, p99 %s ms" %
          (late * 1e3, heard * 1e3, m.group(1), m.group(2)))


def gimbal_frames(seqc, source):
    """(at_s, horizontal) of every gimbal frame of the car's dance, from `seqc compile`."""
    out = subprocess.run([seqc, "compile", "examples/car-dance.yaml", "--emit", "json"],
                         cwd=source, capture_output=True, text=True, check=True).stdout
    frames = []
    for f in json.loads(out)["frames"]:
        m = re.match(r"GimbalServos horizontal=(\d+)", f["packet"])
        if m:
            frames.append((f["at_ms"] / 1000.0, int(m.group(1))))
    return frames


def car(seqc, source):
    frames = gimbal_frames(seqc, source)
    emu = subprocess.Popen([seqc, "emulate", "raspblock"], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True, bufsize=1)
    pty = emu.stdout.readline().strip()
    changes = Lines(emu.stderr)
    udp = free_port()
    proc, lines = start_follow(seqc, source, "examples/car-dance.yaml", pty, "127.0.0.1:%d" % udp)
    master = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    to = ("127.0.0.1", udp)
    master.sendto(sync_packet(OPEN, "show.fseq"), to)
    lines.wait_for("planned")
    time.sleep(0.2)
    t0 = time.monotonic()
    master.sendto(sync_packet(START, "show.fseq"), to)
    jump = 0.0
    t_jump = None
    other_sent = False
    while True:
        time.sleep(0.1)
        e = time.monotonic() - t0
        if e >= 6.0:
            break
        if t_jump is None and e >= 3.2:
            jump, t_jump = 10.0, time.monotonic()
        if not other_sent and e > 2.0:
            other_sent = True
            master.sendto(sync_packet(SYNC, "other.fseq", 40.0, 1600), to)  # ignored
        master.sendto(sync_packet(SYNC, "show.fseq", e + jump, int((e + jump) / FRAME_S)), to)
    t_stop = time.monotonic()
    master.sendto(sync_packet(STOP, "show.fseq"), to)
    code = proc.wait(timeout=10)
    time.sleep(0.3)
    emu.send_signal(2)
    emu.wait(timeout=10)
    text = "\n".join(l for _, l in lines.lines)
    if code != 0:
        fail("follow (car) exited %d:\n%s" % (code, text))
    for want in ("sent the stop", "1 about other files", "re-anchored the stream"):
        if want not in text:
            fail("follow (car) did not say %r:\n%s" % (want, text))

    seen = []  # (arrival, emulator time, field, value)
    for arrived, line in changes.lines:
        # "0.52 s  gimbal.horizontal = 1500" the first time, "... 1500 -> 1498" after.
        m = re.match(r"\s*([\d.]+) s\s+(\S+) (?:= |-?\d+ -> )(-?\d+)$", line)
        if m:
            seen.append((arrived, float(m.group(1)), m.group(2), int(m.group(3))))
    if not seen:
        fail("the emulator reported no change")
    epoch = min(a - t for a, t, _, _ in seen)  # its clock's 0 on ours
    at = [(epoch + t, field, value) for _, t, field, value in seen]
    skew = at[0][0] - t0
    if not 0 <= skew + 0.002 <= FRAME_S:
        fail("the car's first change came %.1f ms after the master's start" % (skew * 1e3))
    after_jump = [a for a, _, _ in at if a >= t_jump]
    if not after_jump or after_jump[0] - t_jump > FRAME_S:
        near = [(round((a - t_jump) * 1e3, 1), f, v) for a, f, v in at if abs(a - t_jump) < 1]
        fail("the car did not follow the 10 s jump within one frame: %s" % near)
    reanchor = after_jump[0] - t_jump
    if any(a > t_stop + 0.05 for a, _, _ in at):
        fail("the car changed after the stop")
    # Each gimbal change against its frame's time on the master's clock (t0, then t0 - 10 s after
    # the jump), leaving out the changes the jump itself brought at once.
    errors = []
    for a, field, value in at:
        if field != "gimbal.horizontal" or t_jump <= a < t_jump + FRAME_S:
            continue
        anchor = t0 if a < t_jump else t0 - 10.0
        dance = a - anchor
        near = [f for f in frames if f[1] == value and abs(f[0] - dance) < 0.2]
        if not near:
            fail("gimbal.horizontal = %d at dance %.3f s matches no frame" % (value, dance))
        errors.append(min((dance - f[0] for f in near), key=abs))
    if len(errors) < 100:
        fail("only %d gimbal changes to measure" % len(errors))
    p50, p99 = percentile(errors, 0.5), percentile(errors, 0.99)
    if p99 > FRAME_S:
        fail("the car's frames were %.1f ms off the master's clock (p99)" % (p99 * 1e3))
    print("car: start skew %.1f ms; re-anchored %.1f ms after the jump; steady-state error "
          "median %.2f ms, p99 %.2f ms over %d frames" %
          (skew * 1e3, reanchor * 1e3, p50 * 1e3, p99 * 1e3, len(errors)))


def main():
    seqc, source = sys.argv[1], sys.argv[2]
    arm(seqc, source)
    car(seqc, source)


if __name__ == "__main__":
    main()
