"""`seqc lsp` over raw standard input and output: framing mistakes, bodies that are no
JSON-RPC, requests out of turn, cancellation and the exit statuses. The process must answer
each as the protocol says and never die.

Usage: raw_stdio_test.py SEQC EXAMPLE.yaml
"""
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from lsp_client import Client  # noqa: E402

failures = []


def check(what, got, want):
    if got != want:
        failures.append(f"{what}: got {got!r}, want {want!r}")


def error_code(message):
    return message.get("error", {}).get("code")


def main():
    seqc, example = sys.argv[1], sys.argv[2]

    # A request before initialize, and the end without shutdown: status 1.
    c = Client(seqc)
    rid = c.request("textDocument/hover", {})
    m = c.response(rid)
    check("request before initialize", error_code(m), -32002)
    c.notify("textDocument/didOpen", {})  # dropped before initialize, no answer
    rid = c.request("initialize", {"capabilities": {}})
    result = c.response(rid)["result"]
    check("serverInfo", result["serverInfo"]["name"], "seqc")
    check("sync", result["capabilities"]["textDocumentSync"],
          {"openClose": True, "change": 2, "save": {"includeText": False}})
    check("exit status without shutdown (end of input)", c.finish(), 1)

    c = Client(seqc)
    c.initialize()
    # Framing: a body that is no JSON, a header without Content-Length, a negative and a huge
    # Content-Length, a header line far too long: each a parse error, and the server reads on.
    # After a framing error the server reads on from the next "Content-Length:", here the one
    # after the long line: its body is read as a message.
    c.raw(b"X-Long: " + b"a" * 5000 + b"\r\nContent-Length: 2\r\n\r\n{}")
    check("header line too long", error_code(c.receive()), -32700)
    check("message after the long line", error_code(c.receive()), -32600)
    c.raw(b"Content-Length: 9\r\n\r\n{not json")
    check("body that is no JSON", error_code(c.receive()), -32700)
    c.raw(b"Content-Type: text/plain\r\n\r\n")
    check("no Content-Length", error_code(c.receive()), -32700)
    c.raw(b"Content-Length: -5\r\n\r\n")
    check("negative Content-Length", error_code(c.receive()), -32700)
    # A body nested a million deep (JSON values are freed recursively): refused unparsed.
    deep = b'{"jsonrpc": "2.0", "id": 1, "method": "x", "params": ' + b"[" * 1000000 + b"]" * \
        1000000 + b"}"
    c.raw(b"Content-Length: %d\r\n\r\n" % len(deep) + deep)
    check("nested a million deep", c.receive(), {"jsonrpc": "2.0", "id": None, "error": {
        "code": -32700, "message": "the message nests more than 256 levels"}})
    # Bodies: not an object, no jsonrpc, a bad id, params of the wrong type, wrong types inside.
    for body, code, what in [
        (b"[1, 2]", -32600, "a batch"),
        (b'{"id": 1, "method": "shutdown"}', -32600, "no jsonrpc"),
        (b'{"jsonrpc": "2.0", "id": {}, "method": "x"}', -32600, "object id"),
        (b'{"jsonrpc": "2.0", "id": 2, "method": 7}', -32600, "method not a string"),
        (b'{"jsonrpc": "2.0", "id": 3, "method": "x", "params": 5}', -32602, "params a number"),
        (b'{"jsonrpc": "2.0", "id": 4, "method": "initialize", "params": {}}', -32600,
         "initialize twice"),
    ]:
        c.raw(b"Content-Length: %d\r\n\r\n" % len(body) + body)
        check(what, error_code(c.receive()), code)
    rid = c.request("seqc/noSuchMethod", {})
    check("unknown method", error_code(c.response(rid)), -32601)
    c.notify("seqc/noSuchNotification", {})  # ignored
    c.notify("textDocument/didChange", {"textDocument": 5})  # wrong shape: ignored
    # A cancelled request is answered with -32800; a cancel for no pending request, nothing.
    c.notify("$/cancelRequest", {"id": 100})
    c.send({"jsonrpc": "2.0", "id": 100, "method": "textDocument/hover", "params": {}})
    check("cancelled request", error_code(c.response(100)), -32800)
    c.notify("$/cancelRequest", {"id": "never-sent"})
    # Two messages in one write, then a document that is no choreography at all.
    a = b'{"jsonrpc": "2.0", "id": 101, "method": "a/b"}'
    b = b'{"jsonrpc": "2.0", "id": 102, "method": "c/d"}'
    c.raw(b"Content-Length: %d\r\n\r\n%sContent-Length: %d\r\n\r\n%s" % (len(a), a, len(b), b))
    check("first of two", c.receive().get("id"), 101)
    check("second of two", c.receive().get("id"), 102)
    c.notify("textDocument/didOpen", {"textDocument": {
        "uri": "file:///nonexistent/list.yaml", "languageId": "yaml", "version": 1,
        "text": "- 1\n- 2\n\x01\x02 binary \u00ff\n"}})
    diags = c.diagnostics("file:///nonexistent/list.yaml")
    check("a plain YAML list has an error", len(diags) >= 1 and diags[0]["severity"], 1)
    # After shutdown, requests are refused; exit then ends with status 0.
    rid = c.request("shutdown")
    check("shutdown", c.response(rid).get("result", "missing"), None)
    rid = c.request("textDocument/hover", {})
    check("request after shutdown", error_code(c.response(rid)), -32600)
    c.notify("exit")
    check("exit status after shutdown", c.proc.wait(10), 0)

    # A body over the limit is refused at once and its bytes dropped as they come.
    c = Client(seqc)
    c.initialize()
    c.raw(b"Content-Length: 99999999999\r\n\r\n" + b"x" * 100000)
    check("huge Content-Length", error_code(c.receive()), -32700)
    check("exit status at the end of input inside a body", c.finish(), 1)

    # exit without shutdown: 1.
    c = Client(seqc)
    c.initialize()
    c.notify("exit")
    check("exit status of exit without shutdown", c.proc.wait(10), 1)

    # A real example with one planted mistake: the diagnostic, then fixed by an edit.
    tmp = tempfile.mkdtemp()
    try:
        path = os.path.join(tmp, "walk.yaml")
        with open(example) as f:
            lines = f.read().split("\n")
        lines[9] = lines[9].replace("time:", "tme:")
        text = "\n".join(lines)
        with open(path, "w") as f:
            f.write(text)
        uri = "file://" + path
        c = Client(seqc)
        c.initialize()
        c.notify("textDocument/didOpen", {"textDocument": {
            "uri": uri, "languageId": "yaml", "version": 1, "text": text}})
        diags = c.diagnostics(uri)
        check("planted mistake", diags, [{
            "range": {"start": {"line": 9, "character": 4}, "end": {"line": 9, "character": 7}},
            "severity": 1, "code": "unknown-key", "source": "seqc",
            "message": "unknown key 'tme' in a move step; did you mean 'time'?"}])
        c.notify("textDocument/didChange", {
            "textDocument": {"uri": uri, "version": 2},
            "contentChanges": [{"range": {"start": {"line": 9, "character": 5},
                                          "end": {"line": 9, "character": 5}}, "text": "i"}]})
        check("fixed", c.diagnostics(uri), [])
        rid = c.request("shutdown")
        c.response(rid)
        c.notify("exit")
        check("exit status", c.proc.wait(10), 0)
    finally:
        shutil.rmtree(tmp)

    for f in failures:
        print("FAIL:", f)
    print(f"{0 if failures else 1} passed, {1 if failures else 0} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
