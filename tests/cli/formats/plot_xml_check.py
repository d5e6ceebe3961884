#!/usr/bin/python3
"""`seqc plot` writes well-formed XML whatever a name holds. A choreography whose section and
pose names hold control characters (which XML 1.0 cannot carry at all, escaped or not), markup
and quotes, and a servo file of the car with the same, are plotted; each SVG must parse with
Python's own XML parser (xml.dom.minidom, expat) and show the section's name as text: the
control characters as U+FFFD, everything else as written.
Usage: plot_xml_check.py SEQC"""
import os
import subprocess
import sys
import tempfile
import xml.dom.minidom

seqc = sys.argv[1]
# As YAML escapes: SOH, ESC, BEL, a vertical tab and a form feed, then markup and quotes.
YAML_NAME = r'"s\x01\e\a\v\f <b>&amp;</b> \"q\" \u00e9 end"'
SHOWN = "s\ufffd\ufffd\ufffd\ufffd\ufffd <b>&amp;</b> \"q\" \u00e9 end"
FILES = {
    "arm.yaml": f"""robot: xarm
name: {YAML_NAME}
poses:
  {YAML_NAME}: {{claw: 300}}
sections:
  {YAML_NAME}:
    steps:
      - move: {YAML_NAME}
        time: 500ms
sequence:
  - section: {YAML_NAME}
  - move: home
    time: 500ms
""",
    "car.yaml": f"""robot: raspblock
name: {YAML_NAME}
sections:
  {YAML_NAME}:
    steps:
      - move: {{pan: 1200, tilt: 1000}}
        time: 500ms
sequence:
  - section: {YAML_NAME}
""",
}
problems = []


def texts(node):
    out = []
    for child in node.childNodes:
        if child.nodeType == child.TEXT_NODE:
            out.append(child.data)
        else:
            out.extend(texts(child))
    return out


with tempfile.TemporaryDirectory() as tmp:
    for name, text in FILES.items():
        path = os.path.join(tmp, name)
        with open(path, "w") as f:
            f.write(text)
        svg = os.path.join(tmp, name + ".svg")
        run = subprocess.run([seqc, "plot", path, "-o", svg], capture_output=True, text=True)
        if run.returncode != 0:
            problems.append(f"{name}: seqc plot exited {run.returncode}: {run.stderr}")
            continue
        try:
            document = xml.dom.minidom.parse(svg)
        except Exception as e:  # expat's ExpatError, or a decoding error
            problems.append(f"{name}: the SVG is not well-formed XML: {e}")
            continue
        shown = [t for t in texts(document) if "end" in t and t.strip().startswith(("s", "section"))]
        if not any(SHOWN in t for t in shown):
            problems.append(f"{name}: no text shows the section's name as {SHOWN!r}: {shown}")
        print(f"{name}: well-formed, the name shown in {len(shown)} places")

for p in problems:
    print("FAIL:", p, file=sys.stderr)
print(f"plot XML: {len(problems)} problems")
sys.exit(1 if problems else 0)
