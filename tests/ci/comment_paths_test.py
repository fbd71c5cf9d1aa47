#!/usr/bin/env python3
"""Every vm/..., irradiance/... and tests/... path a source comment names exists in the tree.

Comments that point at files are how a reader finds the rest of a story; a moved or renamed file
leaves them pointing nowhere. Checked: the comments (// in C++, # in Python, shell and CMake) of the
sources. A path with a placeholder (vm/engines/batch_kernels_<target>.cc, vm/engines/jit_*) must match some
file; a build target named after its source (tests/fuzz/fuzz_mesh) must have one (fuzz_mesh.cc).
Usage: comment_paths_test.py SOURCE_DIR. Prints each stale path as file:line: path and exits 1 on any.
"""
import pathlib
import re
import sys

SOURCE_FOLDERS = ("vm", "irradiance", "tests", "bench", "python")
SUFFIXES = {".h", ".cc", ".py", ".pyi", ".sh", ".cmake", ".txt"}
HASH_COMMENTS = {".py", ".pyi", ".sh", ".cmake", ".txt"}
# A path: a top folder, then name characters; a <placeholder> or * stands for any name.
PATH = re.compile(r"(?<![\w/.-])((?:vm|irradiance|tests)/(?:[\w./*-]|<\w+>)*[\w>*])")


def comment_of(line: str, suffix: str) -> str:
    marker = "#" if suffix in HASH_COMMENTS else "//"
    at = line.find(marker)
    return line[at + len(marker):] if at >= 0 else ""


def exists(root: pathlib.Path, path: str) -> bool:
    if "<" in path or "*" in path:
        return any(root.glob(re.sub(r"<\w+>", "*", path)))
    candidate = root / path
    return candidate.exists() or any(candidate.parent.glob(candidate.name + ".*"))


def stale_paths(root: pathlib.Path, file: pathlib.Path):
    for number, line in enumerate(file.read_text(errors="replace").splitlines(), 1):
        for match in PATH.finditer(comment_of(line, file.suffix)):
            if not exists(root, match.group(1)):
                yield number, match.group(1)


def main() -> int:
    if len(sys.argv) != 2:
        print("usage: comment_paths_test.py SOURCE_DIR", file=sys.stderr)
        return 2
    root = pathlib.Path(sys.argv[1])
    # The checker finds a stale path where there is one, so that an empty report means something.
    found = PATH.findall(comment_of("x = 1;  // see vm/no_such_folder/file.cc.", ".cc"))
    if (found != ["vm/no_such_folder/file.cc"] or exists(root, found[0])
            or not exists(root, "vm/engines/batch_kernels_<target>.cc") or not exists(root, "tests/fuzz/fuzz_mesh")):
        print("the checker itself is broken: it missed a stale path or refused a real one", file=sys.stderr)
        return 1
    failures = 0
    for folder in SOURCE_FOLDERS:
        for file in sorted((root / folder).rglob("*")):
            if file.suffix not in SUFFIXES or not file.is_file() or "node_modules" in file.parts:
                continue
            for number, path in stale_paths(root, file):
                print(f"{file.relative_to(root)}:{number}: {path} does not exist")
                failures += 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
