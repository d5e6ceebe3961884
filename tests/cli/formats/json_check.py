#!/usr/bin/python3
"""Checks `seqc check --format json` as docs/cli.md describes it, on every file given: an
array of diagnostics, each with file, 1-based line and column, severity, rule and message,
and notes with their own locations; the same diagnostics, in the same order, as the text
form prints on stderr (its "path:line:col: error|warning: message" lines); and the exit status
docs/cli.md gives (0 every file valid, 1 any has errors, 5 any could not be read), the same as
the text form's.

The files are checked in few processes (each is slow under the sanitizers): all of them in
both forms, then the invalid ones and the valid ones (told apart by the text form's summary
lines) in JSON, each set with its own exit status.
Usage: json_check.py SEQC FILE..."""
import json
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
import seqc_check_batch as batch  # noqa: E402 (tests/seqc_check_batch.py)

HEADLINE = re.compile(r"^(.+?):(\d+):(\d+): (error|warning|note): (.*)$")
problems = []


def entries_of(where, run, status):
    """The diagnostics of a `--format json` run that must exit with `status`."""
    if run.returncode != status:
        problems.append(f"{where}: exit {run.returncode} with json, docs/cli.md gives {status}")
    if run.stderr:
        problems.append(f"{where}: json printed on stderr: {run.stderr!r}")
    try:
        entries = json.loads(run.stdout)
    except json.JSONDecodeError as e:
        problems.append(f"{where}: not JSON: {e}")
        return []
    errors = sum(1 for e in entries if e.get("severity") == "error")
    if (errors > 0) != (status != 0):
        problems.append(f"{where}: {errors} errors with exit status {run.returncode}")
    return entries


seqc, files = sys.argv[1], sys.argv[2:]
t = batch.run(seqc, ["check", *files])
states, unattributed = batch.verdicts(files, t.stdout)
problems += [f"text form: {p}" for p in unattributed]
status = batch.expected_status(states.values())
if t.returncode != status:
    problems.append(f"all files: exit {t.returncode} with text, docs/cli.md gives {status}")
entries = entries_of("all files", batch.run(seqc, ["check", "--format", "json", *files]), status)

unlocated = [ln for ln in t.stderr.splitlines()
             if re.match(r"^[^:\s]+: (error|warning|note): ", ln)]
if unlocated:
    problems.append(f"text diagnostics without a location: {unlocated}")
text = []
for line in t.stderr.splitlines():
    m = HEADLINE.match(line)
    if m:
        text.append((m.group(4), m.group(1), int(m.group(2)), int(m.group(3)), m.group(5)))
flat = []
for e in entries:
    for key in ("file", "line", "column", "severity", "rule", "message", "notes"):
        if key not in e:
            problems.append(f"entry without '{key}': {e}")
    if e.get("line", 0) < 1 or e.get("column", 0) < 1:
        problems.append(f"entry not located: {e}")
    if e.get("severity") not in ("error", "warning"):
        problems.append(f"severity {e.get('severity')!r}")
    if not re.fullmatch(r"[a-z]+(-[a-z]+)*", e.get("rule", "")):
        problems.append(f"rule id {e.get('rule')!r}")
    flat.append((e.get("severity"), e.get("file"), e.get("line"), e.get("column"),
                 e.get("message")))
    for n in e.get("notes", []):
        if n.get("line", 0) < 1 or n.get("column", 0) < 1:
            problems.append(f"note not located: {n}")
        flat.append(("note", n.get("file"), n.get("line"), n.get("column"), n.get("message")))
if flat != text:
    first = next((i for i, (a, b) in enumerate(zip(flat, text)) if a != b),
                 min(len(flat), len(text)))
    problems.append(f"json and text disagree from diagnostic {first} on "
                    f"({len(flat)} in json, {len(text)} in text):\n"
                    f"  json: {flat[first:first + 3]}\n  text: {text[first:first + 3]}")

# Each kind of file alone, so that a wrong status for either kind cannot hide behind the other.
invalid = [f for f in files if states[f] != "valid"]
valid = [f for f in files if states[f] == "valid"]
if not invalid or not valid:
    problems.append(f"{len(invalid)} invalid and {len(valid)} valid files: give both kinds")
for where, group in (("invalid files", invalid), ("valid files", valid)):
    if group:
        entries_of(where, batch.run(seqc, ["check", "--format", "json", *group]),
                   batch.expected_status(states[f] for f in group))

for p in problems:
    print("FAIL:", p, file=sys.stderr)
print(f"JSON diagnostics: {len(files)} files ({len(invalid)} invalid), {len(entries)} "
      f"diagnostics, {len(problems)} problems")
sys.exit(1 if problems else 0)
