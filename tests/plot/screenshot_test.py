#!/usr/bin/python3
"""`seqc plot` as a person sees it: every example is plotted, the SVG is rendered by headless
Chromium (Debian's `chromium`, --screenshot), and the picture must have the SVG's size and
not be blank: mostly white paper, with the lanes' ink (dark curves, labels) covering a real
part of it and more than a handful of colours.
Usage: screenshot_test.py SEQC FILE..."""
import os
import re
import subprocess
import sys
import tempfile

from PIL import Image

seqc, files = sys.argv[1], sys.argv[2:]
problems = []
with tempfile.TemporaryDirectory() as tmp:
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
        shot = subprocess.run(
            ["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
             f"--user-data-dir={tmp}/profile", f"--window-size={width},{height}",
             f"--screenshot={png}", "file://" + svg],
            capture_output=True, text=True, timeout=120)
        if not os.path.exists(png):
            problems.append(f"{path}: chromium wrote no screenshot: {shot.stderr[-500:]}")
            continue
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
for p in problems:
    print("FAIL:", p, file=sys.stderr)
print(f"plot screenshots: {len(files)} files, {len(problems)} problems")
sys.exit(1 if problems else 0)
