#!/usr/bin/python3
"""The preview of a file with `music:` plays its song and follows the song's clock, tested the
way a person meets it: in headless Chromium (driven over the DevTools pipe, the network made
unreachable), with the page opened from disk.

- The page embeds the song: its <audio id="song"> holds the music file's own bytes as a data:
  URL.
- Driving the audio's clock moves the picture: with the page paused, setting the audio's
  currentTime to the downbeat + 5 s shows t = 5 in `seqc-state`.
- Nothing is fetched: the browser's own log of requests (DevTools' Network domain) holds the
  page's file and data: URLs only.
- Playing, the picture follows the audio, not a timer: moving the audio's currentTime while it
  plays moves the picture with it; at several moments, `seqc-state`'s t is
  the audio's currentTime minus the downbeat (within 50 ms: one frame is 17 ms), the audio having
  advanced by about the wall time played; at 1/2 speed, by about half of it.
The downbeat is read from the example's `music:` block, as the file says it.
Usage: preview_audio_test.py SEQC EXAMPLE.yaml"""
import base64
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
downbeat = float(re.search(r"downbeat:\s*([0-9.]+)s", text).group(1))
song = os.path.join(os.path.dirname(example), re.search(r"file:\s*(\S+)", text).group(1))
problems = []

with tempfile.TemporaryDirectory() as tmp:
    html = os.path.join(tmp, "page.html")
    subprocess.run([seqc, "preview", example, "-o", html], check=True, capture_output=True)
    page = open(html).read()
    m = re.search(r'<audio id="song" preload="auto" src="data:audio/wav;base64,([^"]*)"', page)
    if not m:
        problems.append("the page embeds no <audio id=\"song\"> with a WAV data: URL")
    elif base64.b64decode(m.group(1)) != open(song, "rb").read():
        problems.append("the embedded audio is not the music file's bytes")

    browser = Chromium(tmp, "--autoplay-policy=no-user-gesture-required",
                       "--proxy-server=127.0.0.1:9", "--host-resolver-rules=MAP * ~NOTFOUND")
    try:
        # The browser's own record of every request the page makes: the page itself from disk
        # and its embedded song (data:) are the only ones allowed.
        browser.call("Network.enable")
        browser.call("Page.navigate", {"url": f"file://{html}#t=1"})
        for _ in range(200):
            if browser.eval("(document.getElementById('seqc-state') || {}).textContent || ''"):
                break
            time.sleep(0.05)

        # Paused: the audio's clock, driven from outside, moves the picture.
        shown = browser.eval(f"""new Promise((done) => {{
            const audio = document.getElementById('song');
            audio.addEventListener('seeked', () => setTimeout(() => done(JSON.parse(
                document.getElementById('seqc-state').textContent).t), 50), {{once: true}});
            audio.currentTime = {downbeat} + 5;
        }})""")
        print(f"audio at {downbeat + 5:.3f} s, paused: the page shows t = {shown}")
        if shown != 5:
            problems.append(f"audio driven to downbeat + 5 s: the page shows t = {shown}, not 5")

        def sample():
            return browser.eval("""(() => {
                const audio = document.getElementById('song');
                return [audio.currentTime,
                        JSON.parse(document.getElementById('seqc-state').textContent).t];
            })()""")

        for rate in (1, 0.5):
            browser.eval(f"""(() => {{
                const speed = document.getElementById('speed');
                speed.value = '{rate}';
                speed.dispatchEvent(new Event('change'));
                if (document.getElementById('song').paused)
                    document.getElementById('play').click();
            }})()""")
            time.sleep(0.5)
            first, wall0 = sample(), time.monotonic()
            for _ in range(4):
                time.sleep(0.3)
                audio_t, page_t = sample()
                gap = page_t - (audio_t - downbeat)
                print(f"rate {rate}: audio {audio_t:.3f} s, page t {page_t:.3f} s, "
                      f"page - (audio - downbeat) = {gap * 1000:+.1f} ms")
                if abs(gap) > 0.05:
                    problems.append(f"rate {rate}: page t {page_t} while the audio says "
                                    f"{audio_t - downbeat:.3f}")
            advanced, wall = sample()[0] - first[0], time.monotonic() - wall0
            # The audio moved under the page while it plays: a page on a timer of its own would
            # not follow.
            if rate == 1:
                browser.eval(f"document.getElementById('song').currentTime = {downbeat} + 12")
                time.sleep(0.3)
                audio_t, page_t = sample()
                print(f"audio moved to {downbeat + 12:.3f} s while playing: audio {audio_t:.3f} s,"
                      f" page t {page_t:.3f} s")
                if abs(page_t - (audio_t - downbeat)) > 0.05:
                    problems.append(f"the audio moved to downbeat + 12 s while playing: page t "
                                    f"{page_t}, the audio says {audio_t - downbeat:.3f}")
                first, wall0 = sample(), time.monotonic()
                time.sleep(0.3)
            print(f"rate {rate}: the audio advanced {advanced:.3f} s in {wall:.3f} s of wall time")
            if abs(advanced - rate * wall) > 0.25 * wall:
                problems.append(f"rate {rate}: the audio advanced {advanced:.3f} s in "
                                f"{wall:.3f} s of wall time")
        requests = [p["request"]["url"] for m, p in browser.events
                    if m == "Network.requestWillBeSent"]
        print(f"{len(requests)} requests made by the page: "
              + ", ".join(sorted({u.split(':', 1)[0] + ':' for u in requests})))
        if not any(u.startswith("file://") for u in requests):
            problems.append("the browser recorded no request for the page itself")
        for url in requests:
            if not url.startswith(("file://", "data:")):
                problems.append(f"the page requested {url[:80]}")
    finally:
        browser.close()

for p in problems:
    print("FAIL:", p, file=sys.stderr)
sys.exit(1 if problems else 0)
