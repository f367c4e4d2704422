#!/usr/bin/env python3
"""Fails when a module of src/ramap has no test that names it: src/ramap/<layer>/<module>.cc needs
tests/<layer>/<module>_test.cc (or tests/<layer>/<module>_<what>_test.cc). A module's options
table (<module>_options.cc) is its module's; scripts/check_options.py holds the tables.
Also fails when the fuzz harnesses' build (fuzz/CMakeLists.txt) names a source file that is gone:
that build runs only in CI, so a rename would otherwise be found there first.

    check_tests.py [SOURCE_DIR]
"""

import pathlib
import re
import sys


def missing_fuzz_sources(root):
    listing = root / "fuzz" / "CMakeLists.txt"
    if not listing.exists():
        return []
    named = re.findall(r"\$\{root\}/(src/\S+\.cc)", listing.read_text())
    return [f"fuzz/CMakeLists.txt names {name}, which does not exist"
            for name in named if not (root / name).exists()]


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".")
    source = root / "src" / "ramap"
    tests = root / "tests"
    missing = []
    modules = 0
    for path in sorted(source.rglob("*.cc")):
        if path.stem.endswith("_options"):
            continue
        modules += 1
        layer = path.parent.relative_to(source)
        named = list((tests / layer).glob(f"{path.stem}_test.cc")) + \
            list((tests / layer).glob(f"{path.stem}_*_test.cc"))
        if not named:
            missing.append(f"{path.relative_to(root)}: no tests/{layer}/{path.stem}_test.cc")
    gone = missing_fuzz_sources(root)
    if gone:
        print("\n".join(gone))
        sys.exit(1)
    if missing:
        print("\n".join(missing))
        print(f"check_tests: {len(missing)} of {modules} modules have no test that names them")
        sys.exit(1)
    print(f"check_tests: each of the {modules} modules of src/ramap has a test that names it")


if __name__ == "__main__":
    main()
