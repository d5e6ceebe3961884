#!/usr/bin/python3
"""A name that is markup stays text on the preview page. A show named
`</script><!--<script>alert(1)//` whose one performer has that name too (the name goes into the
page's title, its caption and the JSON island the script reads) is previewed and opened by
headless Chromium from disk: the page must hold exactly its two script elements (the data and
the page's script), load (its `seqc-state` written), open no dialog, and show the name as text
in the performer's caption and the page's title.
Usage: preview_markup_test.py SEQC WALK_YAML"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cdp_pipe import Chromium  # noqa: E402

seqc, walk = sys.argv[1], sys.argv[2]
NAME = "</script><!--<script>alert(1)//"
problems = []

with tempfile.TemporaryDirectory() as tmp:
    shutil.copy(walk, os.path.join(tmp, "walk.yaml"))
    show = os.path.join(tmp, "show.yaml")
    with open(show, "w") as f:
        f.write(f"show: {json.dumps(NAME)}\nperformers:\n  {json.dumps(NAME)}: {{file: walk.yaml}}\n")
    html = os.path.join(tmp, "show.html")
    run = subprocess.run([seqc, "preview", show, "-o", html], capture_output=True, text=True)
    if run.returncode != 0:
        print(f"FAIL: seqc preview: {run.returncode} {run.stderr}", file=sys.stderr)
        sys.exit(1)
    browser = Chromium(tmp, "--proxy-server=127.0.0.1:9", "--host-resolver-rules=MAP * ~NOTFOUND")
    try:
        browser.call("Page.enable")
        browser.call("Page.navigate", {"url": f"file://{html}#t=0.5"})
        state = None
        for _ in range(400):
            state = browser.eval("""(() => {
                const e = document.getElementById('seqc-state');
                return document.readyState === 'complete' && e ? e.textContent : '';
            })()""")
            if state:
                break
            time.sleep(0.025)
        if not state:
            problems.append("the page never wrote seqc-state: its script did not run")
        scripts = browser.eval("document.querySelectorAll('script').length")
        if scripts != 2:
            problems.append(f"the page has {scripts} script elements, not 2")
        captions = browser.eval(
            "[...document.querySelectorAll('.caption')].map((c) => c.textContent)")
        if not captions or not any(c.startswith(NAME + ": ") for c in captions):
            problems.append(f"no caption shows the performer's name as text: {captions}")
        title = browser.eval("document.getElementById('title').textContent")
        if NAME not in (title or ""):
            problems.append(f"the title does not show the show's name as text: {title!r}")
        if state and NAME not in json.loads(state).get("performers", {}):
            problems.append(f"seqc-state does not name the performer: {state[:200]}")
        dialogs = [p for m, p in browser.events if m == "Page.javascriptDialogOpening"]
        if dialogs:
            problems.append(f"the page opened a dialog: {dialogs}")
    finally:
        browser.close()

for p in problems:
    print("FAIL:", p, file=sys.stderr)
print(f"preview of a name that is markup: {len(problems)} problems")
sys.exit(1 if problems else 0)
