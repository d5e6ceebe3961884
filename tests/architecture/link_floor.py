#!/usr/bin/env python3
"""The runtime's libraries below runtime/boards link neither the compiler nor yaml-cpp.

Arguments: LIB=DEP,DEP,... for each library, its whole link closure as CMake resolves it
(tests/architecture/CMakeLists.txt). The forbidden names are written here from
docs/architecture.md; base links fmt alone. Exits 1 naming each library that breaks it.
"""
import sys

FORBIDDEN = {"seqc_compiler", "yaml-cpp", "yaml-cpp::yaml-cpp", "SQLite::SQLite3", "seqc_boards",
             "seqc_cli"}
# What base and the protocol may link at all.
ONLY = {"seqc_base": {"fmt::fmt"}, "seqc_protocol": {"seqc_base", "fmt::fmt"}}


def main() -> int:
    errors = []
    seen = 0
    for arg in sys.argv[1:]:
        lib, _, deps = arg.partition("=")
        closure = {d for d in deps.split(",") if d and d != "seqc_warnings"}
        seen += 1
        for bad in sorted(closure & FORBIDDEN):
            errors.append(f"{lib} links {bad}")
        if lib in ONLY:
            for extra in sorted(closure - ONLY[lib]):
                errors.append(f"{lib} links {extra}; it may link only {sorted(ONLY[lib])}")
    if seen < 8:
        errors.append(f"only {seen} libraries given; the test's arguments are wrong")
    for e in errors:
        print(e)
    print(f"{seen} libraries, {len(errors)} link(s) against docs/architecture.md")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
