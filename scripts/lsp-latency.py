#!/usr/bin/env python3
"""How long `seqc lsp` takes from a keystroke to its diagnostics.

Opens a choreography (by default the example that takes longest to check,
examples/final-step-dance.yaml, whose song is decoded to check the dance against it), then
types N edits one at a time, each an incremental didChange that adds or removes one character
in a comment, and measures the time from sending each to the publishDiagnostics that follows.
The time includes the server's debounce (150 ms after the last change). Prints the median, the
90th and 99th percentiles and the largest, in milliseconds.

Usage: scripts/lsp-latency.py [--seqc build/runtime/cli/seqc] [--edits 50] [FILE]
"""
import argparse
import os
import statistics
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests", "lsp"))
from lsp_client import Client  # noqa: E402


def percentile(values, p):
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(round(p / 100 * (len(ordered) - 1))))]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--seqc", default=os.path.join(ROOT, "build", "runtime", "cli", "seqc"))
    parser.add_argument("--edits", type=int, default=50)
    parser.add_argument("file", nargs="?",
                        default=os.path.join(ROOT, "examples", "final-step-dance.yaml"))
    args = parser.parse_args()
    path = os.path.abspath(args.file)
    text = open(path).read()
    lines = text.split("\n")
    comment = next(i for i, line in enumerate(lines) if line.startswith("#"))
    uri = "file://" + path

    c = Client(args.seqc)
    c.initialize()
    start = time.monotonic()
    c.notify("textDocument/didOpen", {"textDocument": {
        "uri": uri, "languageId": "yaml", "version": 1, "text": text}})
    first = c.diagnostics(uri, timeout=60)
    opened_ms = (time.monotonic() - start) * 1000
    if first:
        print(f"{args.file} has diagnostics: {first[0]['message']}")
        return 1
    samples = []
    for i in range(args.edits):
        at = {"line": comment, "character": 1}
        change = ({"range": {"start": at, "end": at}, "text": "x"} if i % 2 == 0 else
                  {"range": {"start": at, "end": {"line": comment, "character": 2}}, "text": ""})
        start = time.monotonic()
        c.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": i + 2},
                                            "contentChanges": [change]})
        c.diagnostics(uri, timeout=60)
        samples.append((time.monotonic() - start) * 1000)
    rid = c.request("shutdown")
    c.response(rid)
    c.notify("exit")
    c.proc.wait(10)
    print(f"{os.path.relpath(path, ROOT)}: open to diagnostics {opened_ms:.0f} ms; "
          f"keystroke to diagnostics over {len(samples)} edits: "
          f"median {statistics.median(samples):.0f} ms, p90 {percentile(samples, 90):.0f} ms, "
          f"p99 {percentile(samples, 99):.0f} ms, max {max(samples):.0f} ms "
          f"(150 ms of each is the debounce)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
