#!/usr/bin/python3
"""`seqc plot` as a person sees it: every example is plotted, the SVG is opened from disk by
headless Chromium (Debian's `chromium`, one browser driven over the DevTools pipe, its viewport
the SVG's size) and photographed, and the picture must have the SVG's size and not be blank: mostly white paper, with the lanes' ink (dark curves, labels) covering a real
part of it and more than a handful of colours.
Usage: screenshot_test.py SEQC FILE..."""
import base64
import os
import re
import subprocess
import sys
import tempfile
import time

from PIL import Image

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "preview"))
from cdp_pipe import Chromium  # noqa: E402

seqc, files = sys.argv[1], sys.argv[2:]
problems = []


def photograph(browser, url, width, height, png):
    """The page at `url` in a width x height viewport, once loaded and drawn, as a PNG file."""
    browser.call("Emulation.setDeviceMetricsOverride",
                 {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": False})
    browser.call("Page.navigate", {"url": "about:blank"})
    browser.call("Page.navigate", {"url": url})
    for _ in range(400):
        if browser.eval(f"location.href === '{url}' && document.readyState === 'complete'"):
            break
        time.sleep(0.025)
    browser.eval("new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(() => "
                 "r(1))))")
    data = browser.call("Page.captureScreenshot", {"format": "png"})["data"]
    with open(png, "wb") as f:
        f.write(base64.b64decode(data))


with tempfile.TemporaryDirectory() as tmp:
    browser = Chromium(tmp, "--proxy-server=127.0.0.1:9", "--host-resolver-rules=MAP * ~NOTFOUND")
    try:
        for path in files:
            name = os.path.splitext(os.path.basename(path))[0]
            svg = os.path.join(tmp, name + ".svg")
            png = os.path.join(tmp, name + ".png")
            run = subprocess.run([seqc, "plot", path, "-o", svg], capture_output=True, text=True)
            if run.returncode != 0:
                problems.append(f"{path}: seqc plot failed: {run.stderr}")
                continue
            head = open(svg).read(400)
            m = re.search(r'width="(\d+)" height="(\d+)"', head)
            if not m:
                problems.append(f"{path}: no width/height in the SVG")
                continue
            width, height = int(m.group(1)), int(m.group(2))
            if "<script" in open(svg).read():
                problems.append(f"{path}: the SVG has a script")
            photograph(browser, "file://" + svg, width, height, png)
            image = Image.open(png).convert("RGB")
            if image.size != (width, height):
                problems.append(f"{path}: screenshot is {image.size}, the SVG {width}x{height}")
            pixels = list(image.getdata())
            white = sum(1 for p in pixels if p == (255, 255, 255)) / len(pixels)
            ink = sum(1 for p in pixels if sum(p) < 300) / len(pixels)
            colours = len(set(pixels))
            print(f"{name}: {width}x{height}, {white:.1%} white, {ink:.2%} dark ink, "
                  f"{colours} colours")
            if white < 0.5 or white > 0.995 or ink < 0.003 or colours < 8:
                problems.append(f"{path}: looks blank or broken ({white:.1%} white, {ink:.2%} ink, "
                                f"{colours} colours)")
    finally:
        browser.close()
for p in problems:
    print("FAIL:", p, file=sys.stderr)
print(f"plot screenshots: {len(files)} files, {len(problems)} problems")
sys.exit(1 if problems else 0)
