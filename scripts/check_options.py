#!/usr/bin/env python3
"""Holds the options to their declarations (util/option_table.h). Fails, listing each place, when

  1. a range is stated twice: a CheckOption(...) call, or an InputError whose problem begins
     "must", naming a declared option (--Section.option or a command's --option) with a
     requirement that names no other option. A declared option's range
     is its declaration's, and Check() reads it from there (CheckOptionValues); what Check() states
     itself are rules between options ("below --TranslationAveraging.window_frames") and the
     settings no command line reaches (named Struct::field);
  2. an option is outside a table: a command registers an option with CLI11 itself (add_option or
     add_flag anywhere in cli/ but cli/options.h's AddOptionTable);
  3. a message, doc or README names an option nobody declares: every "--Section.option" in src/,
     cli/, python/, docs/, README.md, BENCHMARKS.md and RELIABILITY.md, every "--option" (without
     a section) quoted in a message of src/, cli/ or python/, and every name a message builds from
     a prefix (s = "--Section."; s + "key"), must be a declared name, a former name or a COLMAP
     name of some command's option. A line that quotes a command line of
     COLMAP itself ("colmap mapper --Mapper.ba_local_max_num_iterations ...") is COLMAP's, not
     ramap's, and is passed over;
  4. docs/options.md is not what `ramap options` prints.

    check_options.py SOURCE_DIR RAMAP_BINARY

Prints the three counts on success.
"""

import fnmatch
import pathlib
import re
import subprocess
import sys

SECTIONED = re.compile(r"--([A-Z][A-Za-z0-9]*\.[a-z][a-z0-9_*]*[a-z0-9*])")
QUOTED_PLAIN = re.compile(r'"--([a-z][a-z0-9_]*[a-z0-9])[" :]')
# A command line of COLMAP's own: `colmap <command> ...` (not ramap standing in for it); an
# example of the message an unknown name gets.
COLMAP_COMMAND = re.compile(r"(^|[\s`(\"'/])colmap\s+[a-z_]+|no such")
# Names that stand for any option in prose and comments, and main's own flags.
PLACEHOLDERS = {"Section.option", "Foo.bar", "Foo.baz", "name", "help", "version"}
# Sections of the peers' options, never ramap's: COLMAP 4's global mapper (GLOMAP).
FOREIGN_SECTIONS = ("GlobalMapper.",)


def is_declared(name, names):
    """A name, or a pattern of names ("Mapper.ba_refine_*"), that some command declares."""
    if name in PLACEHOLDERS or name.startswith(FOREIGN_SECTIONS):
        return True
    if "*" in name:
        return any(fnmatch.fnmatchcase(declared, name) for declared in names)
    return name in names


def declared_names(options_markdown):
    """Every name a command accepts, from `ramap options`."""
    names = set()
    for line in options_markdown.splitlines():
        if line.startswith("| `--"):
            names.add(line.split("`")[1][2:])
            names.update(re.findall(r"\((?:formerly|COLMAP:) `--([\w.]+)`\)", line))
        elif line.startswith("- `--"):
            names.add(line.split("`")[1][2:])
    return names


def calls(text, function):
    """The argument text of each call `function(...)` in `text`."""
    found = []
    for match in re.finditer(rf"\b{function}\(", text):
        depth, k = 1, match.end()
        while depth and k < len(text):
            if text[k] == '"':  # a string literal's parentheses are text
                k += 1
                while k < len(text) and text[k] != '"':
                    k += 2 if text[k] == "\\" else 1
            else:
                depth += {"(": 1, ")": -1}.get(text[k], 0)
            k += 1
        found.append(text[match.end():k - 1])
    return found


def range_checks(text):
    """(option named, the rest of the call) of each CheckOption(ok, option, requirement, value)
    and of each InputError(option, "must ...") in `text`."""
    prefixes = dict(re.findall(r'const std::string (\w+) = "([^"]*)";', text))
    checks = []
    for call in calls(text, "CheckOption"):
        prefix_use = re.search(r",\s*(\w+) \+ \"(\w+)\"", call)
        if prefix_use and prefix_use.group(1) in prefixes:
            checks.append((prefixes[prefix_use.group(1)] + prefix_use.group(2),
                           call[prefix_use.end():]))
            continue
        option = re.search(r'"((?:[^"\\]|\\.)*)"', call)
        if option:
            checks.append((option.group(1), call[option.end():]))
    for call in calls(text, "InputError"):
        option = re.match(r'\s*"(--[\w.]+)"\s*,(.*)', call, re.DOTALL)
        if option and re.match(r'\s*"must', option.group(2)):
            checks.append((option.group(1), option.group(2)))
    return checks


def main():
    root = pathlib.Path(sys.argv[1])
    binary = sys.argv[2]
    generated = subprocess.run([binary, "options"], check=True, capture_output=True,
                               text=True).stdout
    names = declared_names(generated)
    problems = []

    if (root / "docs" / "options.md").read_text() != generated:
        problems.append("docs/options.md is not what `ramap options` prints: run "
                        "`build/ramap options > docs/options.md`")

    sources = [p for d in ("src", "cli", "python") for p in sorted((root / d).rglob("*"))
               if p.suffix in (".cc", ".h", ".py")]
    twice = []
    for path in sources:
        for option, rest in range_checks(path.read_text()):
            # A rule between options names the other one in its requirement.
            if option.startswith("--") and option[2:] in names and "--" not in rest:
                requirement = " ".join(re.findall(r'"([^"]*)"', rest))
                twice.append(f"{path.relative_to(root)}: {option} ({requirement})")
    problems += [f"range stated twice (the declaration states it): {t}" for t in twice]

    outside = []
    for path in sorted((root / "cli").glob("*")):
        if path.name == "options.h":
            continue
        for number, line in enumerate(path.read_text().splitlines(), 1):
            if re.search(r"\badd_(option|flag)\(", line):
                outside.append(f"{path.relative_to(root)}:{number}")
    problems += [f"option registered outside a table: {o}" for o in outside]

    pages = sources + sorted((root / "docs").rglob("*.md")) + [
        root / name for name in ("README.md", "BENCHMARKS.md", "RELIABILITY.md")]
    undeclared = []
    for path in pages:
        code = path.suffix in (".cc", ".h", ".py")
        for number, line in enumerate(path.read_text().splitlines(), 1):
            if COLMAP_COMMAND.search(line):
                continue
            found = SECTIONED.findall(line) + (QUOTED_PLAIN.findall(line) if code else [])
            for name in found:
                if not is_declared(name, names):
                    undeclared.append(f"{path.relative_to(root)}:{number}: --{name}")
        # Names a message builds from a prefix: `const std::string s = "--Section."; s + "key"`.
        if code:
            text = path.read_text()
            for variable, prefix in re.findall(r'(\w+) = "--([A-Z]\w*\.\w*)";', text):
                for key in re.findall(rf'\b{variable} \+ "(\w+)"', text):
                    if not is_declared(prefix + key, names):
                        undeclared.append(f"{path.relative_to(root)}: --{prefix + key}")
    problems += [f"names an option nobody declares: {u}" for u in undeclared]

    if problems:
        print("\n".join(problems))
        sys.exit(1)
    print(f"check_options: {len(names)} option names declared; 0 ranges stated twice, "
          f"0 options outside a table, 0 undeclared options named in "
          f"{len(pages)} files")


if __name__ == "__main__":
    main()
