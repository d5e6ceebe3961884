#!/usr/bin/python3
"""What a reader of the documentation meets: every complete choreography shown in README.md and
docs/ (a ```yaml block with both `robot:` and `sequence:` at the top level) passes `seqc check`,
and every relative link points at a file (and heading) that exists.
Usage: docs_test.py SEQC REPO_ROOT"""
import os
import re
import subprocess
import sys
import tempfile

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
            run = subprocess.run([seqc, "check", path], capture_output=True, text=True, cwd=tmp)
            if run.returncode != 0:
                line = text[:m.start()].count("\n") + 2
                problems.append(f"{rel}:{line}: the example does not check:\n{run.stderr}")
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
for p in problems:
    print("FAIL:", p, file=sys.stderr)
print(f"docs: {len(pages)} pages, {blocks} examples checked, {links} links followed, "
      f"{len(problems)} problems")
sys.exit(1 if problems else 0)
