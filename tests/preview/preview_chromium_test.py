#!/usr/bin/python3
"""`seqc preview` as a person sees it. Every example is previewed and opened by headless
Chromium (Debian's `chromium`, one browser driven over the DevTools pipe, each instant a fresh
load of the page) from disk, with the network made unreachable (a proxy on a closed port and a
resolver that finds no host), at several `#t=` instants:

- the page's `seqc-state` (JSON for the instant shown) must give each servo the position
  `seqc simulate --step 1` gives at that millisecond (within 0.5 unit: simulate rounds), and
  the arm's tip its tip columns (within 0.5 mm); a show's performers each against their own
  file;
- a screenshot must have the window's size and not be blank, and for an arm the tip's dot
  (colour #ff00ff) must be drawn where the tip's coordinates put it in the side view, whose
  layout the page documents (formats/preview_html.hpp): the view's corner at page pixel
  (8, 80), 0.4 px per mm, r = 0 at x = 200 and z = 0 at y = 300 inside it; r is the tip's
  distance out along the base's direction, the base angle being (base - 500) * 0.24 degrees on
  the xArm and (base - 1500) * 0.09 degrees on the LeArm (2000 us over 180 degrees);
- the file names no URL and loads nothing (no src/href, @import, url(); a song is embedded as
  a data: URL), and the browser's own log of requests (DevTools' Network domain) holds nothing
  but the pages' files.
It also prints the page's size and load time (a whole `chromium --dump-dom` run, Chromium started
to `seqc-state` dumped, and inside the page) for the longest example.
Usage: preview_chromium_test.py SEQC FILE..."""
import base64
import csv
import io
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time

from PIL import Image

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cdp_pipe import Chromium  # noqa: E402

seqc, files = sys.argv[1], sys.argv[2:]
problems = []
BLOCKED = ["--proxy-server=127.0.0.1:9", "--host-resolver-rules=MAP * ~NOTFOUND"]


def chromium(tmp, *args):
    return subprocess.run(
        ["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
         f"--user-data-dir={tmp}/profile", *BLOCKED, *args],
        capture_output=True, text=True, timeout=120)


def state_at(tmp, html, seconds):
    """seqc-state after a whole `chromium --dump-dom` run (the load-time figures)."""
    run = chromium(tmp, "--dump-dom", f"file://{html}#t={seconds}")
    m = re.search(r'<pre id="seqc-state">([^<]*)</pre>', run.stdout)
    if not m or not m.group(1):
        return None
    return json.loads(m.group(1).replace("&quot;", '"').replace("&amp;", "&"))


def load_at(browser, html, seconds):
    """Loads the page afresh at #t=seconds and returns seqc-state once it is written and the
    page has drawn a frame after it (None if it never is)."""
    url = f"file://{html}#t={seconds}"
    browser.call("Page.navigate", {"url": "about:blank"})
    browser.call("Page.navigate", {"url": url})
    for _ in range(400):
        text = browser.eval(f"""(() => {{
            const e = document.getElementById('seqc-state');
            return location.href === {json.dumps(url)} && document.readyState === 'complete'
                && e ? e.textContent : '';
        }})()""")
        if text:
            browser.eval("new Promise((r) => requestAnimationFrame(() => "
                         "requestAnimationFrame(() => r(1))))")
            return json.loads(text)
        time.sleep(0.025)
    return None


def screenshot(browser, png):
    data = browser.call("Page.captureScreenshot", {"format": "png"})["data"]
    with open(png, "wb") as f:
        f.write(base64.b64decode(data))


def simulated(path):
    run = subprocess.run([seqc, "simulate", path, "--step", "1"], capture_output=True, text=True)
    if run.returncode != 0:
        return None
    rows = list(csv.DictReader(io.StringIO(run.stdout)))
    return {int(r["time_ms"]): r for r in rows}


def compare(label, state, row):
    """The page's servos (and tip) at an instant against simulate's row for that ms."""
    for name, value in state["servos"].items():
        want = row.get(name, "")
        if want == "":
            problems.append(f"{label}: page shows {name}={value}, simulate has it unknown")
        elif abs(float(want) - value) > 0.5 + 1e-9:
            problems.append(f"{label}: {name} is {value} on the page, {want} in simulate")
    for name in row:
        # x, y, z are the car's rocker speeds: the page shows where they take it (check_car).
        if name not in ("time_ms", "x", "y", "z") and not name.startswith("tip_") \
                and row[name] != "" and name not in state["servos"]:
            problems.append(f"{label}: the page does not show {name}")
    if "tip_x" in row:
        want = [float(row["tip_x"]), float(row["tip_y"]), float(row["tip_z"])]
        if "tip" not in state or any(abs(a - b) > 0.5 for a, b in zip(state["tip"], want)):
            problems.append(f"{label}: tip {state.get('tip')} on the page, {want} in simulate")
    elif "tip" in state:
        problems.append(f"{label}: a tip without geometry")


def check_car(label, state, sim, ms):
    """The car's pose: the rocker speeds as cm/s (x right, y forward) and z as degrees per second
    clockwise, each 20 ms sample's speeds held for 20 ms from the start facing up, in mm; between
    samples the page moves in a straight line."""
    x = y = heading = 0.0
    poses = [(0, x, y, heading)]
    t = 0
    end = max(sim)
    while t < end:
        step = min(20, end - t)
        row = sim[t]
        vx, vy, vz = float(row["x"]), float(row["y"]), float(row["z"])
        h = math.radians(heading)
        x += (vx * math.cos(h) + vy * math.sin(h)) * step / 1000
        y += (-vx * math.sin(h) + vy * math.cos(h)) * step / 1000
        heading += vz * step / 1000
        t += step
        poses.append((t, x, y, heading))
    i = max(k for k in range(len(poses)) if poses[k][0] <= ms)
    a = poses[i]
    b = poses[i + 1] if i + 1 < len(poses) else a
    f = 0 if b[0] == a[0] else (ms - a[0]) / (b[0] - a[0])
    want = {"x": 10 * (a[1] + (b[1] - a[1]) * f), "y": 10 * (a[2] + (b[2] - a[2]) * f),
            "heading": a[3] + (b[3] - a[3]) * f}
    car = state.get("car")
    if car is None or any(abs(car[k] - want[k]) > 0.5 for k in want):
        problems.append(f"{label}: car {car} on the page, {want} by the model")


# Each arm profile's base: its position at angle 0 and degrees per unit.
BASE_TURN = {"xarm": (500, 0.24), "learm": (1500, 0.09)}


def profile_of(path):
    m = re.search(r"^(?:robot:|  profile:)\s*([\w-]+)\s*$", open(path).read(), re.MULTILINE)
    return m.group(1) if m else None


def check_tip_pixel(label, png, state, profile):
    image = Image.open(png).convert("RGB")
    w, h = image.size
    px = image.load()
    spots = [(x, y) for y in range(0, min(h, 500)) for x in range(0, min(w, 420))
             if px[x, y][0] > 235 and px[x, y][1] < 40 and px[x, y][2] > 235]
    if not spots:
        problems.append(f"{label}: no #ff00ff tip dot in the side view")
        return
    # A pixel's centre is half a pixel in from its corner.
    cx = sum(p[0] for p in spots) / len(spots) + 0.5
    cy = sum(p[1] for p in spots) / len(spots) + 0.5
    x, y, z = state["tip"]
    if profile not in BASE_TURN:
        problems.append(f"{label}: an arm on profile {profile}, whose base this test does not know")
        return
    zero, degrees = BASE_TURN[profile]
    base = math.radians((state["servos"].get("base", zero) - zero) * degrees)
    r = x * math.cos(base) + y * math.sin(base)
    want_x, want_y = 8 + 200 + 0.4 * r, 80 + 300 - 0.4 * z
    print(f"{label}: tip dot at ({cx:.1f}, {cy:.1f}), expected ({want_x:.1f}, {want_y:.1f})")
    if abs(cx - want_x) > 2 or abs(cy - want_y) > 2:
        problems.append(f"{label}: tip dot at ({cx:.1f}, {cy:.1f}), expected "
                        f"({want_x:.1f}, {want_y:.1f})")


def check_self_contained(path, text):
    # The one src a page may have is its song, embedded as a data: URL.
    for pattern in [r"https?:", r"\bsrc\s*=(?!\"data:audio/)", r"\bhref\s*=", r"@import", r"url\(",
                    r"<link", r"<iframe", r"<img"]:
        if re.search(pattern, text, re.IGNORECASE):
            problems.append(f"{path}: the page has {pattern}")


def performers(path):
    """A show's performers as (name, file), else [(None, path)]."""
    text = open(path).read()
    if not re.search(r"^performers:", text, re.MULTILINE):
        return [(None, path)]
    out = []
    for m in re.finditer(r"^  (\w+): \{file: ([^,}]+)", text, re.MULTILINE):
        out.append((m.group(1), os.path.join(os.path.dirname(path), m.group(2).strip())))
    return out


longest = None
with tempfile.TemporaryDirectory() as tmp:
    browser = Chromium(tmp, *BLOCKED)
    browser.call("Network.enable")
    browser.call("Emulation.setDeviceMetricsOverride",
                 {"width": 1200, "height": 1000, "deviceScaleFactor": 1, "mobile": False})
    try:
        for path in files:
            name = os.path.splitext(os.path.basename(path))[0]
            html = os.path.join(tmp, name + ".html")
            run = subprocess.run([seqc, "preview", path, "-o", html], capture_output=True,
                                 text=True)
            if run.returncode != 0:
                problems.append(f"{path}: seqc preview failed: {run.stderr}")
                continue
            check_self_contained(path, open(html).read())
            parts = [(who, file, simulated(file)) for who, file in performers(path)]
            if any(sim is None for _, _, sim in parts):
                problems.append(f"{path}: seqc simulate failed")
                continue
            end = max(max(sim) for _, _, sim in parts)
            if longest is None or end > longest[0]:
                longest = (end, path, html)
            mid = round(end * 0.55) + 7
            instants = sorted({0, round(end * 0.3), mid, round(end * 0.8), end})
            shown = 0
            png = os.path.join(tmp, name + ".png")
            for ms in instants:
                state = load_at(browser, html, ms / 1000)
                if state is None:
                    problems.append(f"{path}: no seqc-state at t={ms / 1000}")
                    continue
                if abs(state["t"] - ms / 1000) > 1e-9:
                    problems.append(f"{path}: seqc-state t={state['t']} for #t={ms / 1000}")
                for who, file, sim in parts:
                    part = state["performers"][who] if who else state
                    row = sim[min(ms, max(sim))]
                    compare(f"{path} {who or ''} t={ms / 1000}", part, row)
                    if "x" in row:
                        check_car(f"{path} {who or ''} t={ms / 1000}", part, sim, ms)
                shown += 1
                if ms != mid:
                    continue
                # A screenshot mid-way: the page's size, not blank, the tip where it belongs.
                screenshot(browser, png)
                image = Image.open(png).convert("RGB")
                if image.size != (1200, 1000):
                    problems.append(f"{path}: screenshot is {image.size}, not 1200x1000")
                pixels = list(image.getdata())
                white = sum(1 for p in pixels if p == (255, 255, 255)) / len(pixels)
                ink = sum(1 for p in pixels if sum(p) < 300) / len(pixels)
                colours = len(set(pixels))
                print(f"{name}: screenshot at t={ms / 1000}: {white:.1%} white, {ink:.2%} dark "
                      f"ink, {colours} colours")
                if white < 0.3 or white > 0.995 or ink < 0.003 or colours < 8:
                    problems.append(f"{path}: looks blank or broken ({white:.1%} white, "
                                    f"{ink:.2%} ink)")
                if "tip" in state:
                    check_tip_pixel(f"{path} t={ms / 1000}", png, state, profile_of(path))
            print(f"{name}: {shown} instants checked")
        requests = [p["request"]["url"] for m, p in browser.events
                    if m == "Network.requestWillBeSent"]
        pages = {f"file://{os.path.join(tmp, os.path.splitext(os.path.basename(f))[0])}.html"
                 for f in files}
        fetched = [u for u in requests if u.split("#")[0] not in pages and u != "about:blank"]
        print(f"{len(requests)} requests logged by the browser, {len(fetched)} other than the "
              "pages themselves")
        for url in fetched:
            problems.append(f"a page requested {url[:100]}")
    finally:
        browser.close()
    if longest:
        end, path, html = longest
        began = time.monotonic()
        state = state_at(tmp, html, end / 2000)
        took = time.monotonic() - began
        blank = os.path.join(tmp, "blank.html")
        open(blank, "w").write("<!DOCTYPE html><pre id=\"seqc-state\">{}</pre>")
        began = time.monotonic()
        state_at(tmp, blank, 0)
        base = time.monotonic() - began
        # Inside the page: a copy with one more script, last, that notes when it runs.
        timed = os.path.join(tmp, "timed.html")
        open(timed, "w").write(open(html).read().replace(
            "</body>", "<script>document.title = 'ready ' + performance.now()</script></body>"))
        run = chromium(tmp, "--dump-dom", f"file://{timed}#t={end / 2000}")
        m = re.search(r"<title>ready ([0-9.]+)", run.stdout)
        inside = f"{float(m.group(1)):.0f} ms after navigation began" if m else "unknown"
        print(f"longest example {os.path.basename(path)} ({end / 1000:.2f} s): "
              f"{os.path.getsize(html)} bytes, seqc-state after {took:.2f} s in headless "
              f"Chromium ({base:.2f} s for an empty page); the page's script done {inside}")
for p in problems:
    print("FAIL:", p, file=sys.stderr)
print(f"preview in chromium: {len(files)} files, {len(problems)} problems")
sys.exit(1 if problems else 0)
