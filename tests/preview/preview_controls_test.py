#!/usr/bin/python3
"""The preview's controls used as a person uses them: headless Chromium (one browser over the
DevTools pipe) opens the page of a file with a tempo and a meter from disk, and real input
events (a mouse click, the space bar, a choice in the speed list, the loop's check box) drive
it. What the page shows is read from `seqc-state` and compared with what the person did:

- a click on the lanes at the pixel where the plot's axis puts time T shows T (the axis runs from
  x = 150 to 1100 - 24 of the lanes' 1100-wide drawing, 0 to the end of the sequence), paused;
- the space bar plays: the time shown advances with the wall clock; at speed 1/4 by a quarter of
  it; the space bar again pauses, and the time shown stays;
- loop bars 2 to 3 while playing: every time shown lies in bar 2 or 3 and the playhead jumps
  back from the end of bar 3 to the start of bar 2. A bar is (beats per bar) x 60 / tempo
  seconds, read from the file's `tempo` and `meter` as written.
Usage: preview_controls_test.py SEQC FILE.yaml"""
import json
import os
import re
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cdp_pipe import Chromium  # noqa: E402

seqc, example = sys.argv[1], os.path.abspath(sys.argv[2])
text = open(example).read()
tempo = float(re.search(r"^tempo:\s*([0-9.]+)", text, re.MULTILINE).group(1))
beats_per_bar = int(re.search(r"^meter:\s*([0-9]+)/", text, re.MULTILINE).group(1))
bar = beats_per_bar * 60 / tempo  # seconds
problems = []


def check(ok, message):
    if not ok:
        problems.append(message)


with tempfile.TemporaryDirectory() as tmp:
    html = os.path.join(tmp, "page.html")
    subprocess.run([seqc, "preview", example, "-o", html], check=True, capture_output=True)
    end = max(int(row.split(",")[0]) for row in subprocess.run(
        [seqc, "simulate", example, "--step", "1"], check=True, capture_output=True,
        text=True).stdout.splitlines()[1:]) / 1000
    browser = Chromium(tmp, "--proxy-server=127.0.0.1:9", "--host-resolver-rules=MAP * ~NOTFOUND")
    try:
        browser.call("Emulation.setDeviceMetricsOverride",
                     {"width": 1200, "height": 1000, "deviceScaleFactor": 1, "mobile": False})
        browser.call("Page.navigate", {"url": f"file://{html}"})
        for _ in range(400):
            if browser.eval("document.readyState === 'complete' && "
                            "!!document.getElementById('seqc-state').textContent"):
                break
            time.sleep(0.025)

        def shown():
            return json.loads(browser.eval("document.getElementById('seqc-state').textContent"))["t"]

        def playing():
            return browser.eval("document.getElementById('play').textContent") == "pause"

        def key(name, code, text_=""):
            for kind in ("keyDown", "keyUp"):
                browser.call("Input.dispatchKeyEvent", {"type": kind, "key": name, "code": code,
                                                        "text": text_ if kind == "keyDown" else "",
                                                        "windowsVirtualKeyCode": 32})

        def click(x, y):
            for kind in ("mousePressed", "mouseReleased"):
                browser.call("Input.dispatchMouseEvent", {"type": kind, "x": x, "y": y,
                                                          "button": "left", "buttons": 1,
                                                          "clickCount": 1})

        # Scrubbing: a click on the first lanes' drawing (in view below the robot, as the page
        # opens), where the axis puts T.
        box = browser.eval("""(() => {
            const b = document.querySelector('.lanes svg').getBoundingClientRect();
            return [b.left, b.top, b.width, b.height];
        })()""")
        for target in (end * 0.25, end * 0.6):
            x = box[0] + (150 + target / end * (1100 - 150 - 24)) * box[2] / 1100
            click(x, box[1] + 60)
            time.sleep(0.1)
            got = shown()
            # One pixel of the axis is end / 926 seconds; half of it is the most a click misses.
            print(f"click at x={x:.1f}: the page shows t={got}, the axis puts {target:.3f} there")
            check(abs(got - target) <= end / 926, f"a click where the axis puts {target:.3f} s "
                  f"shows t={got}")
            check(not playing(), "a click on the lanes started playing")

        def measure_rate(rate):
            """Plays for about a second at `rate` and returns (advanced, wall)."""
            browser.eval(f"""(() => {{
                const speed = document.getElementById('speed');
                speed.value = '{rate}';
                speed.dispatchEvent(new Event('change'));
            }})()""")
            click(box[0] + (150 + 0.1 * (1100 - 150 - 24)) * box[2] / 1100, box[1] + 60)
            key(" ", "Space", " ")
            time.sleep(0.2)
            t0, w0 = shown(), time.monotonic()
            time.sleep(1.0)
            t1, w1 = shown(), time.monotonic()
            key(" ", "Space", " ")
            return t1 - t0, w1 - w0

        for rate in (1, 0.25):
            advanced, wall = measure_rate(rate)
            print(f"speed {rate}: the page advanced {advanced:.3f} s in {wall:.3f} s of wall time")
            check(abs(advanced - rate * wall) <= 0.1 * wall,
                  f"at speed {rate} the page advanced {advanced:.3f} s in {wall:.3f} s")
            time.sleep(0.1)
            check(not playing(), "the space bar did not pause")
            held = shown()
            time.sleep(0.3)
            check(shown() == held, f"paused at {held}, the page moved on to {shown()}")

        # Loop bars 2 to 3 at speed 1, from inside bar 3.
        browser.eval("""(() => {
            const speed = document.getElementById('speed');
            speed.value = '1';
            speed.dispatchEvent(new Event('change'));
            document.getElementById('loop-from').value = '2';
            document.getElementById('loop-to').value = '3';
        })()""")
        loop_box = browser.eval("""(() => {
            const b = document.getElementById('loop').getBoundingClientRect();
            return [b.left + b.width / 2, b.top + b.height / 2];
        })()""")
        click(*loop_box)
        check(browser.eval("document.getElementById('loop').checked"), "the loop box is unticked")
        start = bar * 2.5
        click(box[0] + (150 + start / end * (1100 - 150 - 24)) * box[2] / 1100, box[1] + 60)
        key(" ", "Space", " ")
        seen, wrapped, last = [], False, None
        began = time.monotonic()
        while time.monotonic() - began < 3 * bar:
            t = shown()
            seen.append(t)
            if last is not None and t < last - bar / 2:
                wrapped = True
            last = t
            time.sleep(0.05)
        key(" ", "Space", " ")
        outside = [t for t in seen if t < bar - 0.02 or t > 3 * bar + 0.05]
        print(f"loop bars 2-3 ({bar:.3f} to {3 * bar:.3f} s): {len(seen)} instants shown, from "
              f"{min(seen):.3f} to {max(seen):.3f} s, wrapped: {wrapped}")
        check(not outside, f"looping bars 2 to 3 showed {outside[:5]}")
        check(wrapped, "looping bars 2 to 3 never went back to bar 2")
    finally:
        browser.close()

for p in problems:
    print("FAIL:", p, file=sys.stderr)
sys.exit(1 if problems else 0)
