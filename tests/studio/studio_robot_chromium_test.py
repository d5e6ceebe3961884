#!/usr/bin/python3
"""The robot follows the studio's page, as a person drives it: `seqc emulate xarm` on a
pseudo-terminal (9600 baud, paced like the real line) is the robot, `seqc studio --port` serves
the page, and headless Chromium clicks on the lanes and presses the space bar (real input events
over the DevTools pipe).

The dance, written here: base to 500 over 2 s, to 900 over 2 s, to 100 over 2 s, with the base's
max_speed at 100 deg/s. On the xArm a degree is 1000/240 units, so that is 416.67 units/s, and
between 2 s and 4 s the line puts the base at 500 + 0.2 x (ms - 2000), between 4 s and 6 s at
900 - 0.4 x (ms - 4000). The emulator powers on with the base at 300.

- Scrubs, alternating near 3 s and near 5 s: each sends the controller one move (a
  MultiServoMove, decoded here from the document's layout: 55 55 LEN 03 COUNT TIME_LO TIME_HI
  then ID POS_LO POS_HI per servo) whose base target is the dance's base at the instant the page
  shows (by the arithmetic above, within 1 unit for the controller's rounding, and exactly what
  `seqc simulate` prints at that millisecond), lasting at least |target - where the base was| /
  416.67 units/s (the slew; the first from 300, where the robot was read to stand).
- The lag from each click to the controller receiving its move (the emulator's record, on the
  same monotonic clock from the instant its terminal appeared) is printed, median and p99.
- Playing from near 5 s: the moves that follow carry the rest of the dance (base 100); paused,
  nothing more arrives after the move under way.
- Saving the file while paused (the last move to 200 instead of 100): the page shows the new
  line's base, 900 - 0.35 x (ms - 4000), at the same instant, and the robot, which finished the
  move under way (to 100), gets one move there, no faster than max_speed.
- SIGINT ends the studio with 130.
Usage: studio_robot_chromium_test.py SEQC"""
import csv
import json
import os
import signal
import statistics
import subprocess
import sys
import tempfile
import threading
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "preview"))
from cdp_pipe import Chromium  # noqa: E402

seqc = sys.argv[1]
problems = []
UNITS_PER_S = 100 * 1000 / 240  # 100 deg/s on the xArm's base
DANCE = """robot:
  profile: xarm
  servos:
    base: {max_speed: 100deg/s}
sequence:
  - move: {base: 500}
    time: 2s
  - move: {base: 900}
    time: 2s
  - move: {base: 100}
    time: 2s
"""


def check(ok, message):
    if not ok:
        problems.append(message)
        print("FAIL:", message)


def base_at(ms):
    if ms <= 4000:
        return 500 + 0.2 * (ms - 2000)
    return 900 - 0.4 * (ms - 4000)


def moves(record_path, origin):
    """Each MultiServoMove the controller took: (arrival on our clock, time_ms, {id: pos})."""
    out = []
    with open(record_path, newline="") as f:
        for row in csv.DictReader(f):
            raw = bytes.fromhex(row["bytes"].replace(" ", ""))
            if row["status"] != "ok" or len(raw) < 7 or raw[:2] != b"\x55\x55" or raw[3] != 3:
                continue
            count, time_ms = raw[4], raw[5] | raw[6] << 8
            targets = {}
            for i in range(count):
                servo = raw[7 + 3 * i:10 + 3 * i]
                targets[servo[0]] = servo[1] | servo[2] << 8
            out.append((origin + float(row["time_s"]), time_ms, targets))
    return out


with tempfile.TemporaryDirectory() as tmp:
    dance = os.path.join(tmp, "base.yaml")
    with open(dance, "w") as f:
        f.write(DANCE)
    link = os.path.join(tmp, "xarm")
    record = os.path.join(tmp, "record.csv")
    emu = subprocess.Popen([seqc, "emulate", "xarm", "--link", link, "--record", record,
                            "--positions", "6=300"],
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    for _ in range(2000):
        if os.path.exists(link):
            break
        time.sleep(0.001)
    # The emulator's record counts from the instant it began to serve, which is when its
    # terminal's link appeared (to the millisecond this loop polls at).
    origin = time.monotonic()
    studio = subprocess.Popen([seqc, "-v", "studio", dance, "--port", link],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    line = studio.stdout.readline().strip()
    if not line.startswith("seqc: studio at http://127.0.0.1:"):
        studio.kill()
        emu.kill()
        raise SystemExit(f"seqc studio printed {line!r}, stderr {studio.stderr.read()!r}")
    said = []
    threading.Thread(target=lambda: said.extend(studio.stderr), daemon=True).start()
    url = line[len("seqc: studio at "):]
    browser = Chromium(tmp)
    clicks = []  # (our clock at the press, the instant the page then showed, in ms)
    try:
        browser.call("Emulation.setDeviceMetricsOverride",
                     {"width": 1200, "height": 1000, "deviceScaleFactor": 1, "mobile": False})
        browser.call("Page.navigate", {"url": url})
        for _ in range(400):
            if browser.eval("document.readyState === 'complete' && "
                            "!!document.getElementById('seqc-state').textContent"):
                break
            time.sleep(0.025)

        def state():
            return json.loads(browser.eval("document.getElementById('seqc-state').textContent"))

        box = browser.eval("""(() => {
            document.querySelector('.lanes svg').scrollIntoView();
            const b = document.querySelector('.lanes svg').getBoundingClientRect();
            return [b.left, b.top, b.width, b.height];
        })()""")

        def click_at(seconds):
            # The lanes' axis runs from x = 150 to 1100 - 24 of the 1100-wide drawing over the
            # dance's 6 s; where the click lands exactly is read back from the page.
            x = box[0] + (150 + seconds / 6.0 * (1100 - 150 - 24)) * box[2] / 1100
            pressed = time.monotonic()
            for kind in ("mousePressed", "mouseReleased"):
                browser.call("Input.dispatchMouseEvent", {"type": kind, "x": x, "y": box[1] + 60,
                                                          "button": "left", "buttons": 1,
                                                          "clickCount": 1})
            clicks.append((pressed, round(state()["t"] * 1000)))

        for i in range(12):
            click_at(3.0 if i % 2 == 0 else 5.0)
            time.sleep(0.35)
        time.sleep(0.6)  # the last slew arrives
        scrubbed_moves = len(clicks)

        # Play from the last scrub (near 5 s) for a second, then pause.
        def space():
            for kind in ("keyDown", "keyUp"):
                browser.call("Input.dispatchKeyEvent", {
                    "type": kind, "key": " ", "code": "Space",
                    "text": " " if kind == "keyDown" else "", "windowsVirtualKeyCode": 32})

        space()
        time.sleep(0.6)
        space()
        paused_at = time.monotonic()
        paused_ms = round(state()["t"] * 1000)
        time.sleep(1.0)

        # A save while paused: the last move now goes to 200, so at the paused instant the line
        # puts the base at 900 - 0.35 x (ms - 4000). The page shows it at the same instant, and
        # the robot, which finished the move under way (to 100), slews there.
        saved_at = time.monotonic()
        with open(dance, "w") as f:
            f.write(DANCE.replace("{base: 100}", "{base: 200}"))
        resaved_base = 900 - 0.35 * (paused_ms - 4000)
        shown = None
        end = time.monotonic() + 5
        while time.monotonic() < end and shown is None:
            now_state = state()
            if abs(now_state["servos"]["base"] - resaved_base) <= 1:
                shown = now_state
            time.sleep(0.005)
        check(shown is not None and round(shown["t"] * 1000) == paused_ms,
              f"the page never showed base {resaved_base:.1f} at {paused_ms} ms: {state()}")
        time.sleep(1.0)
    finally:
        browser.close()
        studio.send_signal(signal.SIGINT)
        try:
            code = studio.wait(timeout=20)
        except subprocess.TimeoutExpired:
            studio.kill()
            code = None
        emu.send_signal(signal.SIGINT)
        emu.wait(timeout=20)
    check(code == 130, f"the studio ended with {code} on SIGINT, not 130")

    got = moves(record, origin)
    check(len(got) >= scrubbed_moves, f"{len(got)} moves arrived for {scrubbed_moves} scrubs")
    # Every scrub's move, in order: the first moves that arrived after each click.
    lags = []
    # The base moves in a straight line from where it is when a move arrives to the move's target
    # over the move's time (the controller's model); it powered on at 300.
    last = (0.0, 300, 300, 0)  # arrival, from, to, time_ms

    def base_when(at):
        arrival, start, end, took = last
        if took == 0 or at >= arrival + took / 1000:
            return end
        return start + (end - start) * (at - arrival) / (took / 1000)
    for n, (pressed, shown_ms) in enumerate(clicks):
        after = [m for m in got if m[0] >= pressed]
        if not after:
            check(False, f"scrub {n} to {shown_ms} ms: no move arrived")
            continue
        arrived, time_ms, targets = after[0]
        want = base_at(shown_ms)
        base = targets.get(6)
        check(base is not None and abs(base - want) <= 1,
              f"scrub {n} to {shown_ms} ms: base {base}, the line puts it at {want:.1f}")
        if base is not None:
            where = base_when(arrived)
            least = abs(base - where) / UNITS_PER_S * 1000
            # 3 ms: the arrival is stamped when the frame's last byte is in, its servos started
            # moving as it was decoded (the model above is that close).
            check(time_ms + 3 >= least,
                  f"scrub {n}: {where:.0f} -> {base} in {time_ms} ms, faster than max_speed "
                  f"(at least {least:.0f} ms)")
            last = (arrived, where, base, time_ms)
        lags.append((arrived - pressed) * 1000)
    # `seqc simulate` agrees with the arithmetic at those instants.
    original = os.path.join(tmp, "original.yaml")
    with open(original, "w") as f:
        f.write(DANCE)
    sim = subprocess.run([seqc, "simulate", original, "--step", "1"], capture_output=True,
                         text=True, check=True).stdout.splitlines()
    header = sim[0].split(",")
    column = header.index("base")
    by_ms = {int(r.split(",")[0]): r.split(",") for r in sim[1:] if r}
    for pressed, shown_ms in clicks:
        simulated = float(by_ms[shown_ms][column])
        check(abs(simulated - base_at(shown_ms)) <= 1,
              f"seqc simulate puts the base at {simulated} at {shown_ms} ms, "
              f"the line at {base_at(shown_ms):.1f}")
    if lags:
        ordered = sorted(lags)
        print(f"scrub -> move received over {len(lags)} scrubs: median "
              f"{statistics.median(lags):.1f} ms, p99 "
              f"{ordered[min(len(ordered) - 1, int(0.99 * len(ordered)))]:.1f} ms "
              f"(a 10-byte move is 10.4 ms of the line at 9600 baud)")
    # Playing carried the dance on toward 100; after the pause nothing new left seqc once the
    # move under way had arrived (a 10-byte move takes 10.4 ms; 150 ms for the page's report).
    played = [m for m in got if clicks and m[0] > clicks[-1][0] + 0.5 and m[0] < paused_at]
    check(any(m[2].get(6) == 100 for m in played),
          f"playing from {clicks[-1][1] if clicks else '?'} ms sent no move to 100: {played}")
    late = [m for m in got if paused_at + 0.15 < m[0] < saved_at]
    check(not late, f"moves arrived after the pause: {late}")
    resaved = [m for m in got if m[0] > saved_at]
    check(len(resaved) == 1 and abs(resaved[0][2].get(6, -99) - resaved_base) <= 1,
          f"after the save the robot got {resaved}, not one move to {resaved_base:.1f}")
    if resaved:
        least = abs(resaved[0][2].get(6, 100) - 100) / UNITS_PER_S * 1000
        check(resaved[0][1] + 3 >= least,
              f"100 -> {resaved[0][2]} in {resaved[0][1]} ms, faster than max_speed "
              f"(at least {least:.0f} ms)")

if problems:
    print(f"0 passed, {len(problems)} failed")
    sys.exit(1)
print("1 passed, 0 failed")
