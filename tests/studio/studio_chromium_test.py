#!/usr/bin/python3
"""`seqc studio` as a person uses it: the studio serves a temporary copy of examples/walk.yaml,
headless Chromium (over the DevTools pipe) opens the URL it printed, a real click on the lanes
puts the playhead at about 4.5 s (the claw holds its grip, 650, from 3.5 s to 5.5 s), and then
the file is edited on disk as an editor saves it:

- the grip changed to 600 (then back, and so on, 20 saves): each time, `seqc-state` shows the new
  claw at the same instant, in place (the page is not reloaded: a mark set on `window` stays),
  and the time from the write to the page showing it is measured: each within 300 ms + 200 ms
  (the studio polls every 50 ms and compiles once a change has held still for one poll, so
  100 ms of the 300 are its own by design; the 200 ms margin is for the shared two-core machine,
  where a build beside the test can hold the browser or seqc off the CPU for that long), and
  the median within 300 ms; the median and p99 are printed;
- a step with an error (a claw value written as markup, `<b>x</b>`): the page shows the
  diagnostic with its line and caret, as text (no <b> element appears), while the dance stays
  as it was; fixed, the box goes away;
- without the token every request gets 403; with it, a path outside the studio's routes
  (/../../etc/passwd, sent as is) gets 404 and none of that file;
- the page reports its playhead (the click's jump, play and pause with the space bar), which
  `seqc -v studio` logs;
- leaving the page (beforeunload sends /stop) ends seqc with 0; SIGINT ends it with 130.
Usage: studio_chromium_test.py SEQC examples/walk.yaml"""
import json
import os
import shutil
import signal
import socket
import statistics
import subprocess
import sys
import tempfile
import threading
import time
import urllib.error
import urllib.request

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "preview"))
from cdp_pipe import Chromium  # noqa: E402

seqc, example = sys.argv[1], os.path.abspath(sys.argv[2])
problems = []
GRIP = "  - move: {claw: 650}                               # grip\n"


def check(ok, message):
    if not ok:
        problems.append(message)
        print("FAIL:", message)


stderr_lines = []  # what seqc -v said, read as it runs


def start_studio(path):
    proc = subprocess.Popen([seqc, "-v", "studio", path], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    line = proc.stdout.readline().strip()
    if not line.startswith("seqc: studio at http://127.0.0.1:"):
        proc.kill()
        raise SystemExit(f"seqc studio printed {line!r}, stderr {proc.stderr.read()!r}")
    threading.Thread(target=lambda: stderr_lines.extend(proc.stderr), daemon=True).start()
    return proc, line[len("seqc: studio at "):]


def reported(mode, seconds=3):
    """The playhead reports seqc -v logged with this mode, waiting for one."""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        found = [line for line in list(stderr_lines) if f" ms, {mode}" in line]
        if found:
            return found
        time.sleep(0.01)
    return []


def status_of(url):
    try:
        with urllib.request.urlopen(url, timeout=5) as r:
            return r.status, r.read()
    except urllib.error.HTTPError as e:
        return e.code, e.read()


with tempfile.TemporaryDirectory() as tmp:
    dance = os.path.join(tmp, "walk.yaml")
    shutil.copy(example, dance)
    original = open(dance).read()
    assert GRIP in original, "the example's grip step moved"

    def save(text):
        with open(dance, "w") as f:
            f.write(text)

    proc, url = start_studio(dance)
    base, token = url.split("/?token=")
    browser = Chromium(tmp)
    try:
        # Without the token (or with another), everything is refused alike.
        check(status_of(base + "/")[0] == 403, "the page without the token is not 403")
        check(status_of(base + "/?token=" + "0" * 32)[0] == 403, "a wrong token is not 403")
        check(status_of(base + "/song")[0] == 403, "/song without the token is not 403")
        # With it, no path is read from the request.
        port = int(base.rsplit(":", 1)[1])
        with socket.create_connection(("127.0.0.1", port), timeout=5) as s:
            s.sendall(f"GET /../../etc/passwd?token={token} HTTP/1.1\r\nHost: x\r\n"
                      "Connection: close\r\n\r\n".encode())
            reply = b""
            while chunk := s.recv(65536):
                reply += chunk
        check(reply.startswith(b"HTTP/1.1 404"), f"/../../etc/passwd: {reply[:40]!r}")
        check(b"root:" not in reply, "/../../etc/passwd served the file")

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

        # The playhead by a real click on the lanes, where the axis (x = 150 to 1100 - 24 of the
        # 1100-wide drawing, 0 to 7.7 s) puts 4.5 s.
        box = browser.eval("""(() => {
            document.querySelector('.lanes svg').scrollIntoView();
            const b = document.querySelector('.lanes svg').getBoundingClientRect();
            return [b.left, b.top, b.width, b.height];
        })()""")
        x = box[0] + (150 + 4.5 / 7.7 * (1100 - 150 - 24)) * box[2] / 1100
        for kind in ("mousePressed", "mouseReleased"):
            browser.call("Input.dispatchMouseEvent", {"type": kind, "x": x, "y": box[1] + 60,
                                                      "button": "left", "buttons": 1,
                                                      "clickCount": 1})
        at = state()["t"]
        check(4.4 <= at <= 4.6, f"the click on the lanes showed {at} s, not about 4.5 s")
        check(state()["servos"]["claw"] == 650, f"claw {state()['servos']['claw']} at {at} s")
        # The page told the studio of the jump.
        scrubs = reported("scrubbed")
        check(any(abs(int(line.split("playhead ")[1].split(" ms")[0]) - at * 1000) <= 1
                  for line in scrubs), f"no playhead report of the scrub to {at} s: {scrubs}")
        browser.eval("window.sameDocument = true")

        def wait_for(predicate, seconds=5):
            end = time.monotonic() + seconds
            while time.monotonic() < end:
                value = predicate()
                if value:
                    return value
                time.sleep(0.002)
            return None

        # 20 saves, each changing the grip, timed from the write to the page showing it.
        times = []
        for i in range(20):
            claw = 600 if i % 2 == 0 else 650
            text = original.replace(GRIP, GRIP.replace("650", str(claw)))
            written = time.monotonic()
            save(text)
            shown = wait_for(lambda: state()["servos"]["claw"] == claw and state())
            took = (time.monotonic() - written) * 1000
            if not shown:
                check(False, f"save {i}: the page never showed claw {claw}")
                break
            times.append(took)
            check(shown["t"] == at, f"save {i}: the playhead moved from {at} to {shown['t']}")
            check(took < 500, f"save {i}: {took:.0f} ms from the save to the page (over 500)")
            time.sleep(0.05)
        check(browser.eval("window.sameDocument === true"), "the page was reloaded")
        if times:
            ordered = sorted(times)
            p99 = ordered[min(len(ordered) - 1, int(0.99 * len(ordered)))]
            median = statistics.median(times)
            print(f"save -> page update over {len(times)} saves: median {median:.0f} ms, "
                  f"p99 {p99:.0f} ms, first {times[0]:.0f} ms")
            check(median < 300, f"median {median:.0f} ms from a save to the page (over 300)")
        last_claw = state()["servos"]["claw"]

        # An error, written as markup: shown as text with its line and caret; the dance stays.
        bad = original.replace(GRIP, "  - move: {claw: \"<b>x</b>\"}\n")
        line = original[:original.index(GRIP)].count("\n") + 1
        save(bad)
        errors = wait_for(lambda: browser.eval(
            "(() => { const b = document.getElementById('studio-errors');"
            " return b && !b.hidden ? b.textContent : ''; })()"))
        check(errors is not None and f"walk.yaml:{line}:" in errors,
              f"the error's line is not on the page: {errors!r}")
        check(errors is not None and "<b>x</b>" in errors and "^" in errors,
              f"the source line and its caret are not on the page: {errors!r}")
        check(browser.eval("document.querySelector('#studio-errors b') === null"),
              "the error's text was read as markup")
        check(state()["servos"]["claw"] == last_claw and state()["t"] == at,
              f"the dance changed under an error: {state()}")
        check(browser.eval("document.querySelectorAll('.lanes svg').length") >= 1,
              "the lanes went away under an error")
        save(original)
        check(wait_for(lambda: browser.eval("document.getElementById('studio-errors').hidden")),
              "the error stayed once the file was fixed")

        # Play and pause with the space bar: each reported.
        for kind in ("keyDown", "keyUp"):
            browser.call("Input.dispatchKeyEvent", {"type": kind, "key": " ", "code": "Space",
                                                    "text": " " if kind == "keyDown" else "",
                                                    "windowsVirtualKeyCode": 32})
        check(reported("playing"), "no playhead report of playing")
        time.sleep(0.2)
        for kind in ("keyDown", "keyUp"):
            browser.call("Input.dispatchKeyEvent", {"type": kind, "key": " ", "code": "Space",
                                                    "text": " " if kind == "keyDown" else "",
                                                    "windowsVirtualKeyCode": 32})
        check(reported("paused"), "no playhead report of pausing")

        # Leaving the page says /stop: seqc ends, with 0.
        browser.call("Page.navigate", {"url": "about:blank"})
        try:
            code = proc.wait(timeout=15)
            check(code == 0, f"seqc studio ended with {code} once the page was left")
        except subprocess.TimeoutExpired:
            check(False, "seqc studio went on after the page was left")
    finally:
        browser.close()
        if proc.poll() is None:
            proc.kill()
            proc.wait()

    # Ctrl-C ends it at once, with 130.
    proc, url = start_studio(dance)
    proc.send_signal(signal.SIGINT)
    try:
        code = proc.wait(timeout=5)
        check(code == 130, f"seqc studio ended with {code} on SIGINT, not 130")
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()
        check(False, "seqc studio went on after SIGINT")

if problems:
    print(f"{len(problems)} problem(s)")
    sys.exit(1)
print("ok")
