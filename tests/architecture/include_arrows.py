#!/usr/bin/env python3
"""Every #include between the project's folders points the way docs/architecture.md says.

The table below is the allowed arrows, written from that document, not read from the code: a
new arrow is a design change and has to be made here and in the document together. Exits 1 and
names each include that breaks the table.
"""
import pathlib
import re
import sys

# Folder -> the folders it may include (besides itself).
COMPILER = {
    "compiler/frontend/source": set(),
    "compiler/frontend/yaml": {"compiler/frontend/source"},
    "compiler/timeline": {"compiler/frontend/source"},
    "compiler/program": {"compiler/frontend/source", "compiler/timeline"},
    "compiler/frontend": {"compiler/frontend/source", "compiler/frontend/yaml", "compiler/program",
                          "compiler/timeline"},
    "compiler/fitting": {"compiler/frontend/source", "compiler/program", "compiler/timeline"},
    "compiler/targets/servo_controller": {"compiler/frontend/source", "compiler/frontend",
                                          "compiler/program", "compiler/timeline",
                                          "compiler/fitting"},
    "compiler/targets/raspblock": {"compiler/frontend/source", "compiler/frontend/yaml",
                                   "compiler/frontend", "compiler/program", "compiler/timeline"},
    "compiler/formats": {"compiler/frontend/source", "compiler/frontend", "compiler/program",
                         "compiler/timeline", "compiler/targets/servo_controller",
                         "compiler/targets/raspblock"},
    "compiler/music": {"compiler/frontend/source", "compiler/frontend", "compiler/timeline"},
}
COMPILER["compiler"] = set(COMPILER) - {"compiler"}  # the driver runs every stage

RUNTIME = {
    "runtime/protocol": set(),
    "compiler": {"runtime/protocol"},
    "runtime/io": {"compiler", "runtime/protocol"},
    "runtime/audio": {"runtime/io", "runtime/protocol"},
    "runtime/transport": {"runtime/io", "runtime/protocol"},
    "runtime/upload": {"runtime/io", "runtime/protocol"},
    "runtime/player": {"runtime/io", "runtime/protocol"},
    "runtime/emulator": {"compiler", "runtime/io", "runtime/protocol", "runtime/transport"},
    "runtime/boards": {"compiler", "runtime/audio", "runtime/emulator", "runtime/io",
                       "runtime/player", "runtime/protocol", "runtime/transport",
                       "runtime/upload"},
    "runtime/cli": {"compiler", "runtime/audio", "runtime/boards", "runtime/emulator",
                    "runtime/io", "runtime/protocol", "runtime/transport", "runtime/upload",
                    },
}

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def owner(path: str, table: dict) -> str | None:
    """The longest folder of `table` that holds `path`."""
    best = None
    for folder in table:
        if path.startswith(folder + "/") and (best is None or len(folder) > len(best)):
            best = folder
    return best


def check(root: pathlib.Path, table: dict, scope: str) -> list[str]:
    errors = []
    for f in sorted((root / scope).rglob("*.[ch]pp")):
        rel = f.relative_to(root).as_posix()
        src = owner(rel, table)
        if src is None:
            continue
        for lineno, line in enumerate(f.read_text(encoding="utf-8").splitlines(), 1):
            m = INCLUDE.match(line)
            if not m:
                continue
            dst = owner(m.group(1), table)
            if dst is None or dst == src or dst in table[src]:
                continue
            errors.append(f"{rel}:{lineno}: {src} may not include {dst} ({m.group(1)})")
    return errors


def main() -> int:
    root = pathlib.Path(sys.argv[1])
    errors = check(root, COMPILER, "compiler")
    errors += check(root, RUNTIME, "compiler") + check(root, RUNTIME, "runtime")
    for e in errors:
        print(e)
    print(f"{len(errors)} include(s) against docs/architecture.md")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
