#!/usr/bin/env python3
"""The ThreadSanitizer stage runs every test its filter names: each such test is in a file it builds.

.ci/tsan runs `vs11_tests --gtest_filter=$tsan_filter`, and its build compiles only the test files
that match VS11_TSAN_TEST_FILES (tests/CMakeLists.txt). A test the filter names in any other file
would silently never run under ThreadSanitizer: this check fails on it instead.
Usage: tsan_selection_test.py SOURCE_DIR FILE_REGEX. Prints each such test and exits 1 on any.
"""
import fnmatch
import pathlib
import re
import sys

# TEST(Suite, Name), TEST_F(...), TEST_P(...), TYPED_TEST(...), and INSTANTIATE_TEST_SUITE_P(Prefix, Suite, ...).
TEST = re.compile(r"^\s*(?:TEST|TEST_F|TEST_P|TYPED_TEST|TYPED_TEST_P)\(\s*(\w+)\s*,\s*(\w+)\s*\)", re.M)
INSTANTIATE = re.compile(r"INSTANTIATE_(?:TEST_SUITE|TYPED_TEST_SUITE)_P\(\s*(\w*)\s*,\s*(\w+)\s*,", re.M)
FILTER = re.compile(r"^tsan_filter='([^']+)'", re.M)


def names_in(text: str):
    """The names GoogleTest gives the file's tests, as far as a filter can see them."""
    prefixes = {}
    for prefix, suite in INSTANTIATE.findall(text):
        prefixes.setdefault(suite, []).append(prefix)
    for suite, name in TEST.findall(text):
        if suite in prefixes:
            for prefix in prefixes[suite]:
                yield f"{prefix}/{suite}.{name}/*" if prefix else f"{suite}.{name}/*"
        else:
            yield f"{suite}.{name}"


def main() -> int:
    source_dir = pathlib.Path(sys.argv[1])
    built = re.compile(sys.argv[2])
    found = FILTER.search((source_dir / ".ci" / "tsan").read_text())
    if not found:
        print(".ci/tsan: no tsan_filter='...' line")
        return 1
    patterns = found.group(1).split(":")
    built_count, missing = 0, []
    for path in sorted((source_dir / "tests").rglob("*_test.cc")):
        relative = "/" + path.relative_to(source_dir).as_posix()
        is_built = built.search(relative) is not None
        built_count += is_built
        for name in names_in(path.read_text()):
            if not is_built and any(fnmatch.fnmatchcase(name, p) for p in patterns):
                missing.append(f"{relative[1:]}: {name} matches the filter, but the TSan build leaves the file out")
    for line in missing:
        print(line)
    if built_count == 0:
        print("the file pattern matches no test file")
        return 1
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
