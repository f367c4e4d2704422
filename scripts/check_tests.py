#!/usr/bin/env python3
"""Fails when a module of src/ramap has no test that names it: src/ramap/<layer>/<module>.cc needs
tests/<layer>/<module>_test.cc (or tests/<layer>/<module>_<what>_test.cc). A module's options
table (<module>_options.cc) is its module's; scripts/check_options.py holds the tables.

    check_tests.py [SOURCE_DIR]
"""

import pathlib
import sys


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
    if missing:
        print("\n".join(missing))
        print(f"check_tests: {len(missing)} of {modules} modules have no test that names them")
        sys.exit(1)
    print(f"check_tests: each of the {modules} modules of src/ramap has a test that names it")


if __name__ == "__main__":
    main()
