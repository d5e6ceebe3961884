#!/usr/bin/python3
"""The markers' labels on the preview's lanes never overlap, as Chromium draws them. A piece of
82 bars at 120 bpm in 4/4 with a section every 2 bars, then a tempo change and an `at:` cue at
the same instant, is previewed and opened by headless Chromium from disk; every label of a
`g.marker` (and the count of hidden ones) is measured: its width as Chromium lays it out
(getBBox), its height one font size above its baseline (the rows are a font size apart, so the
glyphs' boxes with their leading would touch). No two boxes may overlap, every one of the 43
markers keeps its <title>, and "21 labels hidden" counts those left out (41 labels of about
78 px, 22.4 px apart: each row takes every fourth, the rows taking turns, so 21 sections are
drawn; the tempo label takes a free row and the cue's finds none).
Usage: preview_labels_test.py SEQC"""
import json
import os
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cdp_pipe import Chromium  # noqa: E402

seqc = sys.argv[1]
problems = []

steps = "".join("  - section: verse\n" for _ in range(41))
PIECE = ("robot: xarm\ntempo: 120\nmeter: 4/4\nsections:\n  verse:\n"
         "    - move: {base: 510}\n      time: 1bar\n"
         "    - move: {base: 490}\n      time: 1bar\n"
         "sequence:\n" + steps +
         "  - tempo: 100\n  - move: {claw: 300}\n    at: 83bar\n    time: 1b\n")

with tempfile.TemporaryDirectory() as tmp:
    src = os.path.join(tmp, "long.yaml")
    with open(src, "w") as f:
        f.write(PIECE)
    html = os.path.join(tmp, "long.html")
    run = subprocess.run([seqc, "preview", src, "-o", html], capture_output=True, text=True)
    if run.returncode != 0:
        print(f"FAIL: seqc preview: {run.returncode} {run.stderr}", file=sys.stderr)
        sys.exit(1)
    browser = Chromium(tmp, "--proxy-server=127.0.0.1:9", "--host-resolver-rules=MAP * ~NOTFOUND")
    try:
        browser.call("Page.enable")
        browser.call("Page.navigate", {"url": f"file://{html}#t=0"})
        ready = False
        for _ in range(400):
            ready = browser.eval("document.readyState === 'complete' && "
                                 "!!document.getElementById('seqc-state').textContent")
            if ready:
                break
            time.sleep(0.025)
        if not ready:
            problems.append("the page never wrote seqc-state: its script did not run")
        boxes = json.loads(browser.eval("""JSON.stringify(
            [...document.querySelectorAll('g.marker text, text.hidden-labels')].map((t) => {
              const b = t.getBBox();
              const size = parseFloat(t.getAttribute('font-size'));
              const base = parseFloat(t.getAttribute('y'));
              return {text: t.textContent, x: b.x, y: base - size, w: b.width, h: size};
            }))""") or "[]")
        titles = browser.eval("document.querySelectorAll('g.marker > title').length")
    finally:
        browser.close()

if titles != 43:
    problems.append(f"{titles} markers keep a <title>, not 43")
for i, a in enumerate(boxes):
    for b in boxes[i + 1:]:
        if (a["x"] < b["x"] + b["w"] and b["x"] < a["x"] + a["w"]
                and a["y"] < b["y"] + b["h"] and b["y"] < a["y"] + a["h"]):
            problems.append(f"labels overlap: {a} and {b}")
texts = [b["text"] for b in boxes]
if texts.count("section verse") != 21:
    problems.append(f"{texts.count('section verse')} section labels drawn, not 21")
if "21 labels hidden" not in texts:
    problems.append(f"no '21 labels hidden' note: {texts}")

for p in problems:
    print("FAIL:", p, file=sys.stderr)
print(f"preview labels: {len(boxes)} drawn, {len(problems)} problems")
sys.exit(1 if problems else 0)
