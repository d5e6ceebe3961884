"""A minimal LSP client over a `seqc lsp --stdio` process, for the tests and the benchmark.

Reads run on a thread into a queue, so a test waits for a message with a timeout and a
server that stops answering fails the test instead of hanging it.
"""
import json
import queue
import subprocess
import threading


class Client:
    def __init__(self, seqc, args=("lsp", "--stdio"), cwd=None):
        self.proc = subprocess.Popen([seqc, *args], stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, cwd=cwd)
        self.messages = queue.Queue()
        self.next_id = 1
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self):
        out = self.proc.stdout
        while True:
            length = None
            while True:
                line = out.readline()
                if not line:
                    self.messages.put(None)
                    return
                line = line.strip()
                if not line:
                    break
                name, _, value = line.partition(b":")
                if name.strip().lower() == b"content-length":
                    length = int(value)
            body = out.read(length)
            self.messages.put(json.loads(body))

    def raw(self, data: bytes):
        self.proc.stdin.write(data)
        self.proc.stdin.flush()

    def send(self, message):
        body = json.dumps(message).encode()
        self.raw(b"Content-Length: %d\r\n\r\n" % len(body) + body)

    def request(self, method, params=None):
        rid = self.next_id
        self.next_id += 1
        message = {"jsonrpc": "2.0", "id": rid, "method": method}
        if params is not None:
            message["params"] = params
        self.send(message)
        return rid

    def notify(self, method, params=None):
        message = {"jsonrpc": "2.0", "method": method}
        if params is not None:
            message["params"] = params
        self.send(message)

    def receive(self, timeout=10):
        message = self.messages.get(timeout=timeout)
        if message is None:
            raise EOFError("the server closed its output")
        return message

    def wait_for(self, predicate, timeout=10):
        """The first message for which predicate holds (others are dropped)."""
        while True:
            message = self.receive(timeout)
            if predicate(message):
                return message

    def response(self, rid, timeout=10):
        return self.wait_for(lambda m: m.get("id") == rid and "method" not in m, timeout)

    def diagnostics(self, uri, timeout=10):
        return self.wait_for(lambda m: m.get("method") == "textDocument/publishDiagnostics"
                             and m["params"]["uri"] == uri, timeout)["params"]["diagnostics"]

    def initialize(self):
        rid = self.request("initialize", {"processId": None, "rootUri": None,
                                          "capabilities": {}})
        result = self.response(rid)["result"]
        self.notify("initialized", {})
        return result

    def finish(self, timeout=10):
        """Closes standard input and returns the exit status."""
        try:
            self.proc.stdin.close()
        except BrokenPipeError:
            pass
        return self.proc.wait(timeout)
