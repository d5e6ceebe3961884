"""Neovim's built-in LSP client (0.7, headless) against `seqc lsp`: a copy of an example with
`tme:` for `time:` gets the diagnostic at the right place, fixing it in the buffer clears it, and
the inlay hints say when each step starts and how long it lasts.

Usage: nvim_test.py SEQC EXAMPLE.yaml   (skipped, status 77, when nvim is not installed)
"""
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))

EXPECTED = [
    "attached true",
    "published true",
    "diagnostic 9:4-9:7 severity=1 code=unknown-key source=seqc "
    "unknown key 'tme' in a move step; did you mean 'time'?",
    "cleared true",
    # walk.yaml's first steps (0-based lines 8, 10, 12) last 1 s, 800 ms and 600 ms; it names no
    # tempo, so the hints give seconds alone.
    "hint 8 0.000 s \u00b7 1.000 s",
    "hint 10 1.000 s \u00b7 800 ms",
    "hint 12 1.800 s \u00b7 600 ms",
    "stopped true",
]


def main():
    seqc, example = sys.argv[1], sys.argv[2]
    nvim = shutil.which("nvim")
    if nvim is None:
        print("nvim is not installed: skipped")
        return 77
    tmp = tempfile.mkdtemp()
    try:
        path = os.path.join(tmp, "walk.yaml")
        with open(example) as f:
            lines = f.read().split("\n")
        lines[9] = lines[9].replace("time:", "tme:")
        with open(path, "w") as f:
            f.write("\n".join(lines))
        out = os.path.join(tmp, "results.txt")
        env = dict(os.environ, SEQC_BIN=seqc, SEQC_LSP_FILE=path, SEQC_LSP_OUT=out,
                   XDG_STATE_HOME=tmp, XDG_DATA_HOME=tmp, XDG_CACHE_HOME=tmp, HOME=tmp)
        subprocess.run([nvim, "--headless", "-u", "NONE", "-i", "NONE", "-c",
                        "luafile " + os.path.join(HERE, "nvim_client.lua")],
                       env=env, stdin=subprocess.DEVNULL, timeout=60, check=False)
        got = open(out, encoding="utf-8").read().splitlines() if os.path.exists(out) else ["no results written"]
    finally:
        shutil.rmtree(tmp)
    if got != EXPECTED:
        print("got:\n  " + "\n  ".join(got) + "\nwant:\n  " + "\n  ".join(EXPECTED))
        print("0 passed, 1 failed")
        return 1
    print("1 passed, 0 failed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
