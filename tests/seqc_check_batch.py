"""`seqc check` on many files in one process, for the Python-driven tests.

One `seqc check FILE...` prints, on stdout, one summary line per file in the order given
(docs/cli.md), followed for a show file by one line per performer ("walk.yaml (arm): ...").
So the verdict of every file is read from one run instead of one process per file, which
matters most under the sanitizers, where every process start is slow:

- "invalid": its summary (or a performer's) says "N error(s)";
- "unreadable": it has no summary line (the text form then prints only `seqc: error: ...`);
- "valid": anything else (a budget line, "ok (...)", "show with N performers").

The exit status a set of files must get is written here from docs/cli.md, never taken from
seqc: 5 if any file could not be read, else 1 if any has errors, else 0.
"""
import re
import subprocess

_ERRORS = re.compile(r": (\d+) errors?(, \d+ warnings?)?$")

STATUS = {"valid": 0, "invalid": 1, "unreadable": 5}


def run(seqc, args, cwd=None):
    """`seqc ARGS` with its stdout, stderr and exit status captured."""
    return subprocess.run([seqc, *args], capture_output=True, text=True, cwd=cwd)


def verdicts(files, stdout):
    """{file: "valid" | "invalid" | "unreadable"} from the text form's summary lines of
    `seqc check FILES...`, and the problems found reading them (lines that belong to no
    file)."""
    lines = stdout.splitlines()
    found, problems, i = {}, [], 0
    for k, path in enumerate(files):
        label = "<stdin>" if path == "-" else path
        if i >= len(lines) or not lines[i].startswith(label + ": "):
            found[path] = "unreadable"
            continue
        unit = [lines[i]]
        i += 1
        later = [("<stdin>" if f == "-" else f) + ": " for f in files[k + 1:]]
        while i < len(lines) and not any(lines[i].startswith(p) for p in later):
            unit.append(lines[i])  # a performer of this show file
            i += 1
        errors = sum(int(m.group(1)) for m in map(_ERRORS.search, unit) if m)
        found[path] = "invalid" if errors else "valid"
    if i != len(lines):
        problems.append(f"summary lines that belong to no file given: {lines[i:]}")
    return found, problems


def expected_status(states):
    """The exit status docs/cli.md gives `seqc check` for files with these verdicts."""
    states = set(states)
    for state in ("unreadable", "invalid"):
        if state in states:
            return STATUS[state]
    return 0
