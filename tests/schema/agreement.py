#!/usr/bin/python3
"""The JSON Schema and `seqc check` agree on which files are valid.

Every file is judged twice: by the schema (python3-jsonschema, after PyYAML reads the file, as
an editor would) and by `seqc check` (valid: no errors, warnings allowed). Any disagreement
fails, except the files in ALLOWED below, each with the reason a schema cannot express the
check. An allowed file on which they agree also fails, so the list never goes stale. Corpus
files state what they expect on their first line (`# expect: valid|invalid - why`), and seqc
must agree with that too.

seqc checks every file in one process (one per file is slow under the sanitizers): each file's
verdict is its summary line (tests/seqc_check_batch.py), and the run's exit status must be the
one docs/cli.md gives for those verdicts. A file in disagreement is checked again alone, only
to quote its diagnostics.

Usage: agreement.py SEQC SCHEMA FILE...
"""
import json
import os
import sys

import jsonschema
import yaml

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import seqc_check_batch as batch  # noqa: E402 (tests/seqc_check_batch.py)

# Checks a schema cannot express, by file. Keys are paths relative to the repository.
ALLOWED = {
    # Two values compared with each other: JSON Schema has no "min < max".
    "tests/schema/corpus/bad-min-above-max.yaml": "min must be below max",
    # Limits depend on the profile *and* on what the value means: +50 and 50 are the same
    # number to a schema, and relative moves, mirroring and poses are resolved by seqc.
    "tests/schema/corpus/bad-above-max-position.yaml": "position limit",
    "tests/golden/bad-position-above-max.yaml": "position limit (device units and degrees)",
    "tests/golden/bad-relative-out-of-limits.yaml": "relative move past a limit",
    "tests/golden/bad-mirrored-out-of-limits.yaml": "mirrored position past a limit",
    "tests/golden/bad-relative-unknown-start.yaml": "a relative first move of a PWM servo, "
                                                    "which cannot say where it stands",
    # Where the arm's tip can go is geometry: reach, joint limits and the table.
    "tests/golden/bad-tip-moves.yaml": "a tip out of reach, past a joint's limit, below the table",
    # Names defined elsewhere in the file or by the profile.
    "tests/golden/bad-unknown-pose.yaml": "a pose name that is not defined",
    "tests/golden/bad-unknown-servo.yaml": "a servo name the robot does not have",
    "tests/golden/bad-unknown-section.yaml": "a section that is not defined; one that calls itself",
    "tests/golden/bad-mirror-unknown-servo.yaml": "a mirror table naming an undefined servo",
    "tests/golden/bad-mirror-without-table.yaml": "mirror used without a table in robot",
    "tests/golden/bad-duplicate-servo-id.yaml": "two servos with one id",
    "tests/golden/bad-servo-in-two-tracks.yaml": "a servo moved in two tracks",
    "tests/golden/bad-servo-in-nested-tracks.yaml": "a servo moved in two tracks, one nested",
    "tests/golden/bad-car-output-in-two-tracks.yaml": "a car output or the drive in two tracks",
    "tests/golden/bad-tempo-in-together.yaml": "a tempo step inside a track, at any depth",
    # Section parameters: what `$name` becomes is known only where the section is performed.
    "tests/golden/bad-section-unknown-param.yaml": "'with' names a parameter not declared",
    "tests/golden/bad-section-undefined-param.yaml": "'$name' of a parameter not declared",
    "tests/golden/bad-car-section-unknown-param.yaml": "a car section's parameters, by name",
    "tests/golden/bad-section-param-does-not-fit.yaml": "a value that fits no position",
    "tests/golden/bad-home-outside-limits.yaml": "limits that exclude the profile's home",
    # Time: beats at the tempo in force, sums and positions in time.
    "tests/golden/bad-at-in-the-past.yaml": "an 'at' earlier than the steps before it end",
    "tests/golden/bad-beats-without-tempo.yaml": "beats need a tempo set elsewhere",
    "tests/golden/bad-ease-steps-too-short.yaml": "time / steps below 20ms",
    "tests/golden/bad-at-bar-in-the-past.yaml": "a bar position the steps before it passed",
    "tests/golden/bad-meter-off-bar-line.yaml": "a meter change off a bar line",
    "tests/golden/bad-too-many-actions.yaml": "the action budget (255 groups of 1,020)",
    # Include targets: a schema sees one file at a time.
    "tests/golden/bad-error-in-include.yaml": "the mistake is in the included file",
    "tests/golden/bad-include-cycle.yaml": "an include cycle",
    "tests/golden/bad-include-missing.yaml": "an included file that does not exist",
    "tests/golden/bad-include-other-robot.yaml": "an included file for another robot",
    "tests/golden/bad-include-too-deep.yaml": "includes nested too deep",
    # YAML that PyYAML reads differently from the YAML 1.2 seqc follows.
    "tests/golden/bad-duplicate-key.yaml": "PyYAML keeps the last of two equal keys silently",
}


def documentation_problems(schema):
    """What editors show: every key has a title, a description and a markdownDescription
    (directly or through its $ref), every pattern a patternErrorMessage, snippets exist for a
    move, a repeat and a robot definition, and no oneOf (editors report "matches more than
    one" for it)."""
    problems = []
    defs = schema["definitions"]

    def resolve(node):
        while isinstance(node, dict) and "$ref" in node:
            node = defs[node["$ref"].rsplit("/", 1)[1]]
        return node

    # Keys are documented where they are declared; if/then/else/not/anyOf branches only refine
    # (or forbid) keys declared beside them.
    def walk(node, where, declared=True):
        if isinstance(node, list):
            for i, n in enumerate(node):
                walk(n, f"{where}[{i}]", declared)
            return
        if not isinstance(node, dict):
            return
        if "oneOf" in node:
            problems.append(f"{where}: oneOf")
        if "pattern" in node and "patternErrorMessage" not in node:
            problems.append(f"{where}: a pattern without patternErrorMessage")
        for key, sub in (node.get("properties", {}) if declared else {}).items():
            target = resolve(sub)
            if target is True or target is False:
                continue  # if/then branches allow or forbid keys documented elsewhere
            for field in ("title", "description", "markdownDescription"):
                if field not in target and field not in sub:
                    problems.append(f"{where}.properties.{key}: no {field}")
        for key, sub in node.items():
            if key not in ("enum", "const", "required", "defaultSnippets"):
                branch = key in ("if", "then", "else", "not", "anyOf", "allOf")
                walk(sub, f"{where}.{key}", declared and not branch)

    walk(schema, "schema")
    labels = {s["label"] for d in defs.values() if isinstance(d, dict)
              for s in d.get("defaultSnippets", [])}
    labels |= {s["label"] for s in
               defs["choreography"]["properties"]["robot"].get("defaultSnippets", [])}
    for want in ("move", "repeat", "robot definition", "drive", "show"):
        if want not in labels:
            problems.append(f"no defaultSnippet '{want}'")
    return problems


def schema_verdict(validator, path):
    try:
        with open(path, encoding="utf-8") as f:
            doc = yaml.safe_load(f)
    except (yaml.YAMLError, UnicodeDecodeError) as e:
        return False, f"YAML: {str(e).splitlines()[0]}"
    errors = list(validator.iter_errors(doc))
    if not errors:
        return True, ""
    best = jsonschema.exceptions.best_match(errors)
    where = "/".join(str(p) for p in best.absolute_path) or "(top)"
    return False, f"{where}: {best.message[:160]}"


def main():
    seqc, schema_path, files = sys.argv[1], sys.argv[2], sys.argv[3:]
    root = os.getcwd()
    with open(schema_path) as f:
        schema = json.load(f)
    jsonschema.Draft7Validator.check_schema(schema)
    validator = jsonschema.Draft7Validator(schema)
    problems, allowed_seen, agree = documentation_problems(schema), set(), 0
    together = batch.run(seqc, ["check", *files])
    states, unattributed = batch.verdicts(files, together.stdout)
    problems += [f"seqc check: {p}" for p in unattributed]
    status = batch.expected_status(states.values())
    if together.returncode != status:
        problems.append(f"seqc check of every file: exit status {together.returncode}, "
                        f"docs/cli.md gives {status} for these verdicts")

    def stderr_of(path):
        return batch.run(seqc, ["check", path]).stderr

    for path in files:
        rel = os.path.relpath(path, root)
        by_schema, why = schema_verdict(validator, path)
        by_seqc = states[path] == "valid"
        with open(path, encoding="utf-8", errors="replace") as f:
            first = f.readline()
        if first.startswith("# expect: "):
            expected = first.split()[2] == "valid"
            if expected != by_seqc:
                problems.append(f"{rel}: expects {'valid' if expected else 'invalid'}, seqc "
                                f"says {'valid' if by_seqc else 'invalid'}: "
                                f"{stderr_of(path)[:300]}")
        if by_schema == by_seqc:
            agree += 1
            if rel in ALLOWED:
                problems.append(f"{rel}: allowed to disagree ({ALLOWED[rel]}) but agrees; "
                                f"remove it from ALLOWED")
            continue
        if rel in ALLOWED:
            allowed_seen.add(rel)
            continue
        side = ("the schema accepts it, seqc rejects it:\n    " + stderr_of(path).strip()[:400]
                if by_schema else f"seqc accepts it, the schema rejects it: {why}")
        problems.append(f"{rel}: {side}")
    for rel in sorted(set(ALLOWED) - allowed_seen):
        if not any(os.path.relpath(p, root) == rel for p in files):
            problems.append(f"{rel}: in ALLOWED but not checked")
    for p in problems:
        print("FAIL:", p, file=sys.stderr)
    print(f"schema vs seqc check: {len(files)} files, {agree} agree, {len(allowed_seen)} "
          f"allowed disagreements, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
