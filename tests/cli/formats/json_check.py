#!/usr/bin/python3
"""Checks `seqc check --format json` as docs/cli.md describes it, on every file given: an
array of diagnostics, each with file, 1-based line and column, severity, rule and message,
and notes with their own locations; the same diagnostics, in the same order, as the text
form prints on stderr (its "path:line:col: error|warning: message" lines).
Usage: json_check.py SEQC FILE..."""
import json
import re
import subprocess
import sys

HEADLINE = re.compile(r"^(.+?):(\d+):(\d+): (error|warning|note): (.*)$")
problems = []
checked = 0
for path in sys.argv[2:]:
    j = subprocess.run([sys.argv[1], "check", "--format", "json", path], capture_output=True,
                       text=True)
    t = subprocess.run([sys.argv[1], "check", path], capture_output=True, text=True)
    if j.returncode != t.returncode:
        problems.append(f"{path}: exit {j.returncode} with json, {t.returncode} with text")
    try:
        entries = json.loads(j.stdout)
    except json.JSONDecodeError as e:
        problems.append(f"{path}: not JSON: {e}")
        continue
    text = []
    unlocated = [ln for ln in t.stderr.splitlines()
                 if re.match(r"^[^:\s]+: (error|warning|note): ", ln)]
    if unlocated:
        problems.append(f"{path}: text diagnostics without a location: {unlocated}")
    for line in t.stderr.splitlines():
        m = HEADLINE.match(line)
        if m:
            text.append((m.group(4), m.group(1), int(m.group(2)), int(m.group(3)), m.group(5)))
    flat = []
    for e in entries:
        checked += 1
        for key in ("file", "line", "column", "severity", "rule", "message", "notes"):
            if key not in e:
                problems.append(f"{path}: entry without '{key}': {e}")
        if e.get("line", 0) < 1 or e.get("column", 0) < 1:
            problems.append(f"{path}: entry not located: {e}")
        if e.get("severity") not in ("error", "warning"):
            problems.append(f"{path}: severity {e.get('severity')!r}")
        if not re.fullmatch(r"[a-z]+(-[a-z]+)*", e.get("rule", "")):
            problems.append(f"{path}: rule id {e.get('rule')!r}")
        flat.append((e["severity"], e["file"], e["line"], e["column"], e["message"]))
        for n in e.get("notes", []):
            if n.get("line", 0) < 1 or n.get("column", 0) < 1:
                problems.append(f"{path}: note not located: {n}")
            flat.append(("note", n["file"], n["line"], n["column"], n["message"]))
    if flat != text:
        problems.append(f"{path}: json and text disagree:\n  {flat}\n  {text}")
for p in problems:
    print("FAIL:", p, file=sys.stderr)
print(f"JSON diagnostics: {len(sys.argv) - 2} files, {checked} diagnostics, "
      f"{len(problems)} problems")
sys.exit(1 if problems else 0)
