#!/usr/bin/python3
"""What a reader of the documentation meets: every complete choreography shown in README.md and
docs/ (a ```yaml block with both `robot:` and `sequence:` at the top level) passes `seqc check`,
every diagnostic shown has its caret under the column it names, and every relative link points
at a file (and heading) that exists. The tutorial's xArm files also play live on `emu:xarm`
at 9600 baud without a late move. The examples are checked by one `seqc check` of them all
(a process per example is slow under the sanitizers), each judged by its summary line.
Usage: docs_test.py SEQC REPO_ROOT"""
import os
import re
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import seqc_check_batch as batch  # noqa: E402 (tests/seqc_check_batch.py)

seqc, root = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
pages = [os.path.join(root, "README.md"), os.path.join(root, "CHANGELOG.md")]
for dirpath, _, names in os.walk(os.path.join(root, "docs")):
    pages += [os.path.join(dirpath, n) for n in sorted(names) if n.endswith(".md")]


def slug(heading):
    """GitHub's anchor for a heading: lower case, punctuation dropped, spaces to '-'."""
    text = re.sub(r"[`*_]", "", heading.strip().lower())
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


problems, blocks, links = [], 0, 0
examples = []  # (file written, where it is shown)
with tempfile.TemporaryDirectory() as tmp:
    for page in pages:
        rel = os.path.relpath(page, root)
        text = open(page, encoding="utf-8").read()
        for i, m in enumerate(re.finditer(r"```yaml\n(.*?)```", text, re.S)):
            body = m.group(1)
            if not (re.search(r"(?m)^robot:", body) and re.search(r"(?m)^sequence:", body)):
                continue
            blocks += 1
            path = os.path.join(tmp, f"{os.path.basename(page)}-{i}.yaml")
            with open(path, "w") as f:
                f.write(body)
            examples.append((path, f"{rel}:{text[:m.start()].count(chr(10)) + 2}"))
        # A diagnostic as seqc prints it: "path:L:C: ...", "  N | source", "    | ^".
        lines = text.splitlines()
        for n, line in enumerate(lines[:-2]):
            head = re.match(r"^\S+?:(\d+):(\d+): (error|warning|note): ", line)
            src = re.match(r"^ *(\d+) \| (.*)$", lines[n + 1])
            caret = re.match(r"^ *\| (\s*)\^$", lines[n + 2])
            if not (head and src and caret):
                continue
            blocks += 1
            if int(src.group(1)) != int(head.group(1)):
                problems.append(f"{rel}:{n + 1}: quotes line {src.group(1)}, names {head.group(1)}")
            if len(caret.group(1)) != int(head.group(2)) - 1:
                problems.append(f"{rel}:{n + 3}: caret at column {len(caret.group(1)) + 1}, "
                                f"the diagnostic names column {head.group(2)}")
        for m in re.finditer(r"\]\(([^)\s]+)\)", text):
            target = m.group(1)
            if re.match(r"^[a-z]+:", target):
                continue
            links += 1
            file_part, _, anchor = target.partition("#")
            dest = os.path.normpath(os.path.join(os.path.dirname(page), file_part)) if file_part \
                else page
            if not os.path.exists(dest):
                problems.append(f"{rel}: link to {target}: no such file")
                continue
            if anchor and dest.endswith(".md"):
                heads = [slug(h) for h in re.findall(r"(?m)^#+ (.*)$",
                                                     open(dest, encoding="utf-8").read())]
                if anchor not in heads:
                    problems.append(f"{rel}: link to {target}: no heading '#{anchor}'")
    if examples:
        paths = [path for path, _ in examples]
        run = batch.run(seqc, ["check", *paths], cwd=tmp)
        states, unattributed = batch.verdicts(paths, run.stdout)
        problems += [f"seqc check: {p}" for p in unattributed]
        if run.returncode != batch.expected_status(states.values()):
            problems.append(f"seqc check of the examples: exit status {run.returncode}, "
                            f"docs/cli.md gives {batch.expected_status(states.values())}")
        for path, where in examples:
            if states[path] != "valid":
                alone = batch.run(seqc, ["check", path], cwd=tmp)
                problems.append(f"{where}: the example does not check:\n{alone.stderr}")
    # The tutorial's files are played as its reader plays them: live on the emulated xArm at its
    # 9600 baud, in emulated time, with no move late (a late move fails the play, exit 1).
    for path, where in examples:
        if not where.startswith("docs/tutorial.md:") or "robot: xarm" not in open(path).read():
            continue
        blocks += 1
        played = batch.run(seqc, ["play", path, "--port", "emu:xarm"], cwd=tmp)
        if played.returncode != 0 or "seqc: played " not in played.stderr:
            problems.append(f"{where}: does not play on emu:xarm at 9600 baud:\n{played.stderr}")
for p in problems:
    print("FAIL:", p, file=sys.stderr)
print(f"docs: {len(pages)} pages, {blocks} examples and diagnostics checked, {links} links "
      f"followed, {len(problems)} problems")
sys.exit(1 if problems else 0)
