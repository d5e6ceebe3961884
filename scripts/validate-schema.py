#!/usr/bin/python3
"""Validates choreography files against schemas/seqc.schema.json.

Usage: validate-schema.py SCHEMA FILE...   (exit 1 if any file does not validate)
Run with Debian's /usr/bin/python3 (python3-jsonschema, python3-yaml).
"""
import json
import sys

import jsonschema
import yaml


def main(argv):
    with open(argv[1]) as f:
        schema = json.load(f)
    jsonschema.Draft7Validator.check_schema(schema)
    validator = jsonschema.Draft7Validator(schema)
    failed = 0
    for path in argv[2:]:
        with open(path) as f:
            doc = yaml.safe_load(f)
        errors = sorted(validator.iter_errors(doc), key=lambda e: list(e.absolute_path))
        for e in errors:
            where = "/".join(str(p) for p in e.absolute_path) or "(top)"
            print(f"{path}: {where}: {e.message}", file=sys.stderr)
        if errors:
            failed += 1
        else:
            print(f"{path}: valid")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
