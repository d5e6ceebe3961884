#!/usr/bin/env python3
"""Every #include between the project's folders points the way docs/architecture.md says.

The table below is the allowed arrows, written from that document, not read from the code: a
new arrow is a design change and has to be made here and in the document together. Every arrow
points down the layers base <- protocol <- compiler <- runtime, and inside the compiler down its
stages; no folder may include one above it. Exits 1 and names each include that breaks the table
(and any source folder the table does not know, so a new folder cannot slip past it).
"""
import pathlib
import re
import sys

# Folder -> the folders it may include (besides itself). A folder's own subfolders that have no
# row of their own belong to it.
ARROWS = {
    "base": set(),
    "protocol": {"base"},
    # The compiler's stages, in pipeline order.
    "compiler/frontend/yaml": {"base"},
    "compiler/timeline": {"base"},
    "compiler/program": {"base", "protocol", "compiler/timeline"},
    "compiler/frontend": {"base", "protocol", "compiler/frontend/yaml", "compiler/program",
                          "compiler/timeline"},
    "compiler/fitting": {"base", "compiler/program", "compiler/timeline"},
    "compiler/targets/servo_controller": {"base", "protocol", "compiler/frontend",
                                          "compiler/program", "compiler/timeline",
                                          "compiler/fitting"},
    "compiler/targets/raspblock": {"base", "protocol", "compiler/frontend/yaml",
                                   "compiler/frontend", "compiler/program", "compiler/timeline"},
    "compiler/formats": {"base", "protocol", "compiler/frontend", "compiler/program",
                         "compiler/timeline", "compiler/targets/servo_controller",
                         "compiler/targets/raspblock", "compiler/music"},
    "compiler/music": {"base", "compiler/frontend", "compiler/timeline"},
    # The runtime: the OS boundaries first, the board table and the command line last.
    "runtime/io": {"base"},
    "runtime/audio": {"base", "runtime/io"},
    "runtime/transport": {"base", "protocol", "runtime/io"},
    "runtime/upload": {"base", "protocol", "runtime/io"},
    "runtime/player": {"base", "protocol", "runtime/io"},
    "runtime/emulator": {"base", "protocol", "runtime/io", "runtime/transport"},
    "runtime/boards": {"base", "protocol", "compiler", "runtime/audio", "runtime/emulator",
                       "runtime/io", "runtime/player", "runtime/transport", "runtime/upload"},
    # The editor's language server: the compiler's answers about one file, over JSON-RPC.
    "runtime/lsp": {"base", "protocol", "compiler", "runtime/io"},
    # The live studio and following a show's clock drive a board, as the command line does.
    "runtime/studio": {"base", "protocol", "compiler", "runtime/audio", "runtime/boards",
                       "runtime/emulator", "runtime/io", "runtime/player", "runtime/transport",
                       "runtime/upload"},
    "runtime/follow": {"base", "protocol", "compiler", "runtime/audio", "runtime/boards",
                       "runtime/emulator", "runtime/io", "runtime/player", "runtime/transport",
                       "runtime/upload"},
    "runtime/cli": {"base", "protocol", "compiler", "runtime/audio", "runtime/boards",
                    "runtime/emulator", "runtime/follow", "runtime/io", "runtime/lsp",
                    "runtime/studio", "runtime/transport", "runtime/upload"},
}
# The compiler's driver (compiler/*.cpp) runs every stage.
ARROWS["compiler"] = {"base", "protocol"} | {f for f in ARROWS if f.startswith("compiler/")}

# Seen from outside the compiler, all of it is one folder.
COMPILER_STAGES = [f for f in ARROWS if f.startswith("compiler/")]

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def owner(path: str) -> str | None:
    """The longest folder of the table that holds `path`."""
    best = None
    for folder in ARROWS:
        if path.startswith(folder + "/") and (best is None or len(folder) > len(best)):
            best = folder
    return best


def allowed(src: str, dst: str) -> bool:
    if dst == src or dst in ARROWS[src]:
        return True
    # A runtime folder allowed "compiler" may include any of its stages.
    return dst in COMPILER_STAGES and "compiler" in ARROWS[src] and not src.startswith("compiler")


def main() -> int:
    root = pathlib.Path(sys.argv[1])
    errors = []
    for top in ("base", "protocol", "compiler", "runtime"):
        for f in sorted((root / top).rglob("*.[ch]pp")):
            rel = f.relative_to(root).as_posix()
            src = owner(rel)
            if src is None:
                errors.append(f"{rel}: in no folder of the table")
                continue
            for lineno, line in enumerate(f.read_text(encoding="utf-8").splitlines(), 1):
                m = INCLUDE.match(line)
                if not m:
                    continue
                dst = owner(m.group(1))
                if dst is None or allowed(src, dst):
                    continue
                errors.append(f"{rel}:{lineno}: {src} may not include {dst} ({m.group(1)})")
    for e in errors:
        print(e)
    print(f"{len(errors)} include(s) against docs/architecture.md")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
