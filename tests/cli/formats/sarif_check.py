#!/usr/bin/python3
"""Checks `seqc check --format sarif` against what SARIF 2.1.0 (OASIS standard) requires.

The rules below are written from the specification's text, object by object: which
properties are required, their types and ranges, and which property names each object may
have. It also checks the exit status: the one docs/cli.md gives (0 every file valid, 1 any has
errors, 5 any could not be read), the same as the text form's.

The files are checked in few processes (each is slow under the sanitizers): the text form once,
to learn which files are valid; then SARIF for the invalid ones together, the valid ones
together, and all of them, whose results must be the two sets' results, in order.
Usage: sarif_check.py SEQC FILE...
"""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
import seqc_check_batch as batch  # noqa: E402 (tests/seqc_check_batch.py)

errors = []


def fail(where, what):
    errors.append(f"{where}: {what}")


def only(obj, where, allowed):
    if not isinstance(obj, dict):
        fail(where, "must be an object")
        return False
    for key in obj:
        if key not in allowed:
            fail(where, f"property '{key}' is not defined for this object")
    return True


def check_message(m, where):
    # §3.11: a message has text or id (at least one).
    if only(m, where, {"text", "id", "markdown", "arguments", "properties"}):
        if "text" not in m and "id" not in m:
            fail(where, "a message needs 'text' or 'id'")
        if "text" in m and not (isinstance(m["text"], str) and m["text"]):
            fail(where, "'text' must be a non-empty string")


def check_region(r, where):
    # §3.30: lines and columns are 1-based integers; a text region needs startLine.
    if not only(r, where, {"startLine", "startColumn", "endLine", "endColumn", "charOffset",
                           "charLength", "byteOffset", "byteLength", "snippet", "message",
                           "sourceLanguage", "properties"}):
        return
    if "startLine" not in r and "charOffset" not in r and "byteOffset" not in r:
        fail(where, "a region needs startLine, charOffset or byteOffset")
    for key in ("startLine", "startColumn", "endLine", "endColumn"):
        if key in r and not (isinstance(r[key], int) and not isinstance(r[key], bool)
                             and r[key] >= 1):
            fail(where, f"'{key}' must be an integer >= 1, got {r[key]!r}")


def check_physical(p, where):
    # §3.29: a physical location has an address or an artifact location (at least one).
    if not only(p, where, {"address", "artifactLocation", "region", "contextRegion",
                           "properties"}):
        return
    if "artifactLocation" not in p and "address" not in p:
        fail(where, "needs 'artifactLocation' or 'address'")
    a = p.get("artifactLocation")
    if a is not None and only(a, where + ".artifactLocation",
                              {"uri", "uriBaseId", "index", "description", "properties"}):
        uri = a.get("uri")
        if not isinstance(uri, str) or not uri or " " in uri:
            fail(where, f"'uri' must be a URI reference, got {uri!r}")
    if "region" in p:
        check_region(p["region"], where + ".region")


def check_location(loc, where, ids):
    # §3.28: id (optional) is an integer >= -1, unique within the result.
    if not only(loc, where, {"id", "physicalLocation", "logicalLocations", "message",
                             "annotations", "relationships", "properties"}):
        return
    if "id" in loc:
        if not isinstance(loc["id"], int) or loc["id"] < -1:
            fail(where, "'id' must be an integer >= -1")
        elif loc["id"] in ids:
            fail(where, f"id {loc['id']} repeats")
        ids.add(loc["id"])
    if "physicalLocation" in loc:
        check_physical(loc["physicalLocation"], where + ".physicalLocation")
    if "message" in loc:
        check_message(loc["message"], where + ".message")


def check_log(log, where):
    # §3.13: a log has version "2.1.0" and runs; $schema, if present, is a URI.
    if not only(log, where, {"$schema", "version", "runs", "inlineExternalProperties",
                             "properties"}):
        return 0
    if log.get("version") != "2.1.0":
        fail(where, f"version must be \"2.1.0\", got {log.get('version')!r}")
    if "$schema" in log and not str(log["$schema"]).startswith("http"):
        fail(where, "$schema must be a URI")
    runs = log.get("runs")
    if not isinstance(runs, list):
        fail(where, "'runs' is required and must be an array")
        return 0
    results = 0
    for i, run in enumerate(runs):
        w = f"{where}.runs[{i}]"
        # §3.14: a run has a tool; §3.18: a tool has a driver; §3.19: a driver has a name.
        if not only(run, w, {"tool", "results", "invocations", "artifacts", "columnKind",
                             "originalUriBaseIds", "language", "properties"}):
            continue
        tool = run.get("tool")
        if not only(tool, w + ".tool", {"driver", "extensions", "properties"}):
            continue
        driver = tool.get("driver")
        if not only(driver, w + ".tool.driver", {"name", "version", "semanticVersion",
                                                 "informationUri", "rules", "properties",
                                                 "fullName", "organization"}):
            continue
        if not isinstance(driver.get("name"), str) or not driver["name"]:
            fail(w, "tool.driver.name is required")
        rules = driver.get("rules", [])
        rule_ids = []
        for k, rule in enumerate(rules):
            rw = f"{w}.tool.driver.rules[{k}]"
            # §3.49: a reportingDescriptor has an id; descriptions have text.
            if only(rule, rw, {"id", "name", "shortDescription", "fullDescription", "help",
                               "helpUri", "defaultConfiguration", "properties"}):
                if not isinstance(rule.get("id"), str) or not rule["id"]:
                    fail(rw, "'id' is required")
                rule_ids.append(rule.get("id"))
                for d in ("shortDescription", "fullDescription"):
                    if d in rule and not isinstance(rule[d].get("text"), str):
                        fail(rw, f"{d} needs text")
        if len(set(rule_ids)) != len(rule_ids):
            fail(w, "rule ids repeat")
        for j, res in enumerate(run.get("results", [])):
            rw = f"{w}.results[{j}]"
            results += 1
            # §3.27: a result has a message; level is one of four; ruleIndex matches ruleId.
            if not only(res, rw, {"ruleId", "ruleIndex", "rule", "kind", "level", "message",
                                  "locations", "relatedLocations", "fingerprints",
                                  "partialFingerprints", "properties"}):
                continue
            if "message" not in res:
                fail(rw, "'message' is required")
            else:
                check_message(res["message"], rw + ".message")
            if res.get("level", "warning") not in ("none", "note", "warning", "error"):
                fail(rw, f"level {res['level']!r}")
            if "ruleIndex" in res:
                idx = res["ruleIndex"]
                if not isinstance(idx, int) or idx < -1 or idx >= len(rules):
                    fail(rw, f"ruleIndex {idx!r} out of range")
                elif idx >= 0 and rules[idx].get("id") != res.get("ruleId"):
                    fail(rw, "ruleIndex and ruleId name different rules")
            if "ruleId" in res and res["ruleId"] not in rule_ids:
                fail(rw, f"ruleId {res['ruleId']!r} is not among the driver's rules")
            locations = res.get("locations", [])
            if not locations:
                fail(rw, "seqc gives every result a location")
            for k, loc in enumerate(locations):
                check_location(loc, f"{rw}.locations[{k}]", set())
                if "physicalLocation" not in loc:
                    fail(rw, "seqc gives every location a physical location")
            ids = set()
            for k, loc in enumerate(res.get("relatedLocations", [])):
                check_location(loc, f"{rw}.relatedLocations[{k}]", ids)
    return results


def run_sarif(seqc, files, where, status):
    """The SARIF log of `seqc check --format sarif FILES`, checked, and its results; the run
    must exit with `status` and print nothing on stderr."""
    p = batch.run(seqc, ["check", "--format", "sarif", *files])
    if p.returncode != status:
        fail(where, f"exit status {p.returncode}, docs/cli.md gives {status}")
    if p.stderr:
        fail(where, f"stderr is not empty: {p.stderr!r}")
    try:
        log = json.loads(p.stdout)
    except json.JSONDecodeError as e:
        fail(where, f"not JSON: {e}")
        return None, []
    count = check_log(log, where)
    results = [r for run in log.get("runs", []) if isinstance(run, dict)
               for r in run.get("results", [])] if isinstance(log, dict) else []
    if count != len(results):
        fail(where, f"{count} results checked, {len(results)} found")
    errors = sum(1 for r in results if isinstance(r, dict) and r.get("level") == "error")
    if (errors > 0) != (status != 0):
        fail(where, f"{errors} error results with exit status {p.returncode}")
    return log, results


def main():
    seqc, files = sys.argv[1], sys.argv[2:]
    text = batch.run(seqc, ["check", *files])
    states, problems = batch.verdicts(files, text.stdout)
    for p in problems:
        fail("text form", p)
    invalid = [f for f in files if states[f] != "valid"]
    valid = [f for f in files if states[f] == "valid"]
    if not invalid or not valid:
        fail("files", f"{len(invalid)} invalid and {len(valid)} valid files: give both kinds")
    if text.returncode != batch.expected_status(states.values()):
        fail("text form", f"exit status {text.returncode}, docs/cli.md gives "
                          f"{batch.expected_status(states.values())}")
    sets = {}
    for name, group in (("invalid files", invalid), ("valid files", valid),
                        ("all files", invalid + valid)):
        if group:
            status = batch.expected_status(states[f] for f in group)
            sets[name] = run_sarif(seqc, group, name, status)
    together = sets.get("all files", (None, []))[1]
    apart = sets.get("invalid files", (None, []))[1] + sets.get("valid files", (None, []))[1]
    if together != apart:
        fail("all files", f"{len(together)} results together, {len(apart)} in the two sets "
                          "(or they differ)")
    for e in errors:
        print("FAIL:", e, file=sys.stderr)
    print(f"SARIF: {len(files)} files ({len(invalid)} invalid), {len(together)} results "
          f"checked, {len(errors)} problems")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
