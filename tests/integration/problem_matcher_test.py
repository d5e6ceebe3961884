#!/usr/bin/python3
"""The GitHub Actions problem matcher (.github/seqc-problem-matcher.json) applied to what
`seqc check` prints, the way the runner applies it: line by line, the first matching pattern
gives file, line, column, severity and message. Every error and warning of every bad golden
file must become one annotation equal to the diagnostic in `--format json`, and no other line
(source quotes, carets, notes, summaries) may match. All files are checked by one `seqc check`
in each form (a process per file is slow under the sanitizers): the text form prints them in
the order given, as the JSON array lists them.
Usage: problem_matcher_test.py SEQC MATCHER FILE..."""
import json
import re
import subprocess
import sys

seqc, matcher_path, files = sys.argv[1], sys.argv[2], sys.argv[3:]
with open(matcher_path) as f:
    matcher = json.load(f)["problemMatcher"]
assert len(matcher) == 1 and matcher[0]["owner"] == "seqc"
pattern = matcher[0]["pattern"][0]
regexp = re.compile(pattern["regexp"])
problems = []
text = subprocess.run([seqc, "check", *files], capture_output=True, text=True)
found = []
for line in (text.stdout + text.stderr).splitlines():
    m = regexp.search(line)
    if m:
        found.append({"file": m.group(pattern["file"]), "line": int(m.group(pattern["line"])),
                      "column": int(m.group(pattern["column"])),
                      "severity": m.group(pattern["severity"]),
                      "message": m.group(pattern["message"])})
machine = json.loads(subprocess.run([seqc, "check", "--format", "json", *files],
                                    capture_output=True, text=True).stdout)
want = [{k: e[k] for k in ("file", "line", "column", "severity", "message")} for e in machine]
annotations = len(found)
if not want:
    problems.append("no diagnostics at all: give files with mistakes")
for i, (got, expected) in enumerate(zip(found, want)):
    if got != expected:
        problems.append(f"annotation {i}:\n  matcher: {got}\n  json:    {expected}")
        break
if len(found) != len(want):
    extra = found[len(want):] or want[len(found):]
    problems.append(f"{len(found)} annotations, {len(want)} diagnostics in json; first "
                    f"unmatched: {extra[0]}")
for p in problems:
    print("FAIL:", p, file=sys.stderr)
print(f"problem matcher: {len(files)} files, {annotations} annotations, {len(problems)} problems")
sys.exit(1 if problems else 0)
