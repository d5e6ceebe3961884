"""Headless Chromium driven over the DevTools protocol on --remote-debugging-pipe: commands go
in on the browser's fd 3 and replies come out on its fd 4, each a JSON message ended by a NUL
byte. Enough of the protocol for a test to open one page and evaluate script in it; no network
port is opened."""
import json
import os
import signal
import subprocess


class Chromium:
    def __init__(self, tmp, *flags):
        to_r, to_w = os.pipe()
        from_r, from_w = os.pipe()

        def as_fd3_and_fd4():
            os.dup2(to_r, 3)
            os.dup2(from_w, 4)

        self.proc = subprocess.Popen(
            ["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
             "--remote-debugging-pipe", f"--user-data-dir={tmp}/cdp-profile", *flags,
             "about:blank"],
            preexec_fn=as_fd3_and_fd4, pass_fds=(3, 4, to_r, from_w), start_new_session=True,
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(to_r)
        os.close(from_w)
        self.out = os.fdopen(to_w, "wb", buffering=0)
        self.inp = os.fdopen(from_r, "rb", buffering=0)
        self.pending = b""
        self.events = []  # every event the browser sent, as (method, params), in order
        self.last_id = 0
        self.session = None
        page = next(t for t in self.call("Target.getTargets")["targetInfos"]
                    if t["type"] == "page")
        self.session = self.call("Target.attachToTarget",
                                 {"targetId": page["targetId"], "flatten": True})["sessionId"]

    def call(self, method, params=None):
        self.last_id += 1
        message = {"id": self.last_id, "method": method, "params": params or {}}
        if self.session:
            message["sessionId"] = self.session
        self.out.write(json.dumps(message).encode() + b"\0")
        while True:
            while b"\0" not in self.pending:
                chunk = self.inp.read(65536)
                if not chunk:
                    raise RuntimeError("chromium closed its pipe")
                self.pending += chunk
            raw, self.pending = self.pending.split(b"\0", 1)
            reply = json.loads(raw)
            if "method" in reply and "id" not in reply:
                self.events.append((reply["method"], reply.get("params", {})))
            elif reply.get("id") == self.last_id:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply["result"]

    def eval(self, expression):
        """The expression's value (promises awaited), as JSON-able data."""
        result = self.call("Runtime.evaluate", {"expression": expression, "returnByValue": True,
                                                "awaitPromise": True})
        if "exceptionDetails" in result:
            raise RuntimeError(f"{expression}: {result['exceptionDetails']}")
        return result["result"].get("value")

    def close(self):
        """Closes the browser and waits for every process of it: a renderer still writing into
        the profile would make the caller's temporary directory fail to go away."""
        try:
            self.session = None
            self.call("Browser.close")
            self.proc.wait(timeout=10)
        except (RuntimeError, OSError, subprocess.TimeoutExpired):
            pass
        try:
            os.killpg(self.proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        self.proc.wait()
