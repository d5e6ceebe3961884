#!/usr/bin/python3
"""Runs the mutation catalogue (scripts/mutants/catalogue.txt) against a scratch copy.

Each catalogue entry names a file, a line of code to find (literal text, matched once) and
what to put in its place. A mutation is *killed* when its tests fail (or time out), *survives*
when they all pass, *no longer applies* when its text is not found exactly once (the code moved
on: update the entry), and is *stillborn* when it does not build (a bad entry, not a test gap).
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import time

# Tests that need a package install, a browser or a fuzzer build, and the slow soak and
# benchmarks: a mutation's default test set leaves them out so one mutation costs seconds.
DEFAULT_EXCLUDE = ("deb_package|cmake_install|configures_without|plot_renders|fuzz_replay|"
                   "man_page|completion|pre_commit|_bench_runs|upload_soak")
FIELDS = {"id", "layer", "file", "find", "replace", "tests", "why"}


def parse_catalogue(path):
    entries, entry = [], {}
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    for n, raw in enumerate(lines + [""], 1):
        line = raw.rstrip()
        if line.startswith("#"):
            continue
        if not line:
            if entry:
                entries.append(entry)
                entry = {}
            continue
        key, sep, value = line.partition(": ")
        if not sep and line.endswith(":"):
            key, value = line[:-1], ""
        elif not sep:
            sys.exit(f"{path}:{n}: error: expected 'key: value', got '{line}'")
        if key not in FIELDS:
            sys.exit(f"{path}:{n}: error: unknown key '{key}' (keys: {', '.join(sorted(FIELDS))})")
        if key in entry:
            sys.exit(f"{path}:{n}: error: '{key}' given twice in one entry")
        entry[key] = value
        entry.setdefault("_line", n)
    seen = set()
    for e in entries:
        for k in ("id", "layer", "file", "find", "replace"):
            if k not in e:
                sys.exit(f"{path}:{e['_line']}: error: entry has no '{k}'")
        if e["id"] in seen:
            sys.exit(f"{path}:{e['_line']}: error: id '{e['id']}' is used twice")
        if e["find"] == e["replace"]:
            sys.exit(f"{path}:{e['_line']}: error: '{e['id']}' replaces its text with itself")
        seen.add(e["id"])
    return entries


def run(cmd, cwd=None, timeout=None, log=None):
    """Runs cmd; returns (exit status or None on timeout, seconds)."""
    start = time.monotonic()
    try:
        p = subprocess.run(cmd, cwd=cwd, stdout=log or subprocess.DEVNULL,
                           stderr=subprocess.STDOUT, timeout=timeout)
        return p.returncode, time.monotonic() - start
    except subprocess.TimeoutExpired:
        return None, time.monotonic() - start


def sync_scratch(root, scratch):
    """Copies the tracked and untracked-but-not-ignored files into the scratch copy. Only files
    whose content differs are written, and they get a new modification time (not the source's),
    so the scratch build redoes exactly what changed since its last run, even when the source
    file is older than an object the scratch build made from a previous version of it."""
    files = subprocess.run(["git", "ls-files", "-z", "-c", "-o", "--exclude-standard"], cwd=root,
                           check=True, capture_output=True).stdout.split(b"\0")
    os.makedirs(scratch, exist_ok=True)
    for rel in files:
        if not rel:
            continue
        src = os.path.join(root.encode(), rel)
        dst = os.path.join(scratch.encode(), rel)
        if not os.path.isfile(src):
            continue
        with open(src, "rb") as f:
            content = f.read()
        try:
            with open(dst, "rb") as f:
                if f.read() == content:
                    continue
        except FileNotFoundError:
            os.makedirs(os.path.dirname(dst), exist_ok=True)
        with open(dst, "wb") as f:
            f.write(content)
        shutil.copymode(src, dst)
    # A file the tree no longer has goes from the copy too: a source left behind would still be
    # compiled (the build globs its folders) and define twice what its successor defines.
    keep = {rel for rel in files if rel}
    for folder, dirs, names in os.walk(scratch.encode()):
        rel_folder = os.path.relpath(folder, scratch.encode())
        if rel_folder == b".":
            dirs[:] = [d for d in dirs if d not in (b"build", b"logs", b".git")]
        for name in names:
            rel = os.path.normpath(os.path.join(rel_folder, name))
            if rel not in keep:
                os.remove(os.path.join(folder, name))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--root", required=True)
    ap.add_argument("--list", action="store_true", help="print the catalogue and stop")
    ap.add_argument("--timeout", type=int, default=600, help="seconds for one mutation's tests")
    ap.add_argument("words", nargs="*", help="run only ids containing one of these words")
    args = ap.parse_args()

    catalogue = os.path.join(args.root, "scripts", "mutants", "catalogue.txt")
    entries = parse_catalogue(catalogue)
    if args.words:
        entries = [e for e in entries if any(w in e["id"] for w in args.words)]
        if not entries:
            print(f"seqc: error: no mutation id contains {' or '.join(args.words)}",
                  file=sys.stderr)
            return 2
    if args.list:
        for e in entries:
            print(f"{e['id']:<34} {e['layer']:<9} {e['file']}")
            print(f"    - {e['find'].strip()}")
            print(f"    + {e['replace'].strip()}")
        print(f"{len(entries)} mutations")
        return 0

    scratch = os.environ.get("SEQC_MUTANTS_DIR", "/tmp/seqc-mutants")
    build = os.path.join(scratch, "build")
    logs = os.path.join(scratch, "logs")
    sync_scratch(args.root, scratch)
    os.makedirs(logs, exist_ok=True)
    with open(os.path.join(logs, "baseline.log"), "w") as log:
        status, _ = run(["cmake", "-S", scratch, "-B", build, "-G", "Ninja",
                         "-DCMAKE_BUILD_TYPE=Release"], log=log)
        if status == 0:
            print("mutants: building the unmutated scratch copy ...", file=sys.stderr, flush=True)
            status, _ = run(["cmake", "--build", build], log=log)
    if status != 0:
        print(f"seqc: error: the unmutated copy does not build; see {logs}/baseline.log",
              file=sys.stderr)
        return 2

    results = []
    for e in entries:
        path = os.path.join(scratch, e["file"])
        started = time.monotonic()
        outcome, detail = "", ""
        original = None
        if os.path.isfile(path):
            with open(path, encoding="utf-8") as f:
                original = f.read()
        find = e["find"].replace("<newline>", "\n")
        count = original.count(find) if original is not None else 0
        if count != 1:
            outcome = "no longer applies"
            detail = "file is gone" if original is None else f"text found {count} times"
        else:
            log_path = os.path.join(logs, e["id"] + ".log")
            try:
                with open(path, "w", encoding="utf-8") as f:
                    f.write(original.replace(find, e["replace"].replace("<newline>", "\n")))
                with open(log_path, "w") as log:
                    status, _ = run(["cmake", "--build", build, "--target",
                                     *targets_of(build, e.get("tests"))], log=log)
                    if status != 0:
                        outcome, detail = "stillborn", "does not build"
                    else:
                        cmd = ["ctest", "--test-dir", build, "-j", str(os.cpu_count() or 2),
                               "--timeout", "300", "--stop-on-failure"]
                        cmd += ["-R", e["tests"]] if e.get("tests") else []
                        cmd += ["-E", excluded(e.get("tests"))]
                        status, _ = run(cmd, timeout=args.timeout, log=log)
                        if status is None:
                            outcome, detail = "killed", "tests timed out"
                        elif status != 0:
                            outcome = "killed"
                            detail = first_failure(log_path)
                        else:
                            outcome, detail = "survived", e.get("why", "")
            finally:
                with open(path, "w", encoding="utf-8") as f:
                    f.write(original)
        seconds = time.monotonic() - started
        results.append((e, outcome, detail, seconds))
        print(f"{outcome:<18} {e['id']:<34} {seconds:6.1f} s  {detail}", flush=True)

    # Leave the scratch build matching the unmutated tree for the next run.
    run(["cmake", "--build", build])
    print()
    print(f"{'id':<34} {'layer':<9} {'result':<18} detail")
    for e, outcome, detail, _ in results:
        print(f"{e['id']:<34} {e['layer']:<9} {outcome:<18} {detail}")
    counts = {k: sum(1 for r in results if r[1] == k)
              for k in ("killed", "survived", "no longer applies", "stillborn")}
    applied = counts["killed"] + counts["survived"]
    score = f"{100 * counts['killed'] / applied:.0f} %" if applied else "n/a"
    print(f"\nmutation score {score}: {counts['killed']} killed, {counts['survived']} survived, "
          f"{counts['no longer applies']} no longer apply, {counts['stillborn']} stillborn "
          f"(of {len(results)})")
    return 0 if counts["survived"] == 0 and counts["stillborn"] == 0 else 1


def excluded(tests):
    """DEFAULT_EXCLUDE less what the entry's tests name themselves (a benchmark whose run checks
    promises, such as fit_bench_runs, runs when an entry asks for it)."""
    return "|".join(x for x in DEFAULT_EXCLUDE.split("|") if x not in (tests or ""))


def targets_of(build, tests):
    """The build targets a mutation's tests run: each test command's executable, and any
    executable of the build tree among its arguments (the python checks get `seqc` that way),
    so a mutation relinks only what its tests use. Everything, when the tests cannot be listed."""
    cmd = ["ctest", "--test-dir", build, "--show-only=json-v1", "-E", excluded(tests)]
    cmd += ["-R", tests] if tests else []
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        return ["all"]
    targets = {"seqc"}  # tests that run the binary name it only at compile time (SEQC_BIN)
    for t in json.loads(p.stdout).get("tests", []):
        for word in t.get("command", []):
            if word.startswith(build + os.sep) and os.access(word, os.X_OK) and \
                    os.path.isfile(word):
                targets.add(os.path.basename(word))
    return sorted(targets)


def first_failure(log_path):
    """The first failed test's name, from ctest's summary."""
    with open(log_path, errors="replace") as f:
        for line in f:
            if "***Failed" in line or "***Timeout" in line or "***Exception" in line:
                parts = line.split(":", 1)
                return "by " + (parts[1].split()[0] if len(parts) > 1 else line.strip())
    return "tests failed"


if __name__ == "__main__":
    sys.exit(main())
