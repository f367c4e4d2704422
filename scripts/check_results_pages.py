#!/usr/bin/env python3
"""Checks that the results pages stay one page, name where every table came from, and that the
references to their sections still resolve.

Usage: check_results_pages.py SOURCE_DIR
  Exit 0 with a one-line summary when every rule holds; exit 1 listing every problem; exit 2 on a
  usage error. Standard library only.

Rules:
  1. BENCHMARKS.md has at most 600 lines.
  2. Every Markdown table of BENCHMARKS.md names a commit. A table is a run of consecutive lines
     whose first non-blank character is '|', outside fenced code blocks. Its window is the 12 lines
     above its first line and the 6 lines below its last line, each side cut at the nearest heading
     (a commit stated in another section does not describe this table); the table's own rows are
     not part of it (a hash in a row is data, not where the table came from). The window must hold
     a commit hash: 7 to 40 lowercase hex digits with at least one letter and one digit (e.g.
     "commit abc1234", "at abc1234", "dea328f1ed-modified"), or 7 to 40 hex digits right after the
     word "commit" or "commits" (a hash of digits alone, "Commit 1815299").
  3. Every such table names the CPU model of the machine it ran on, in the same window or in the
     paragraph under its section's heading (the first block of non-blank lines after it): a known
     model name (AMD EPYC, Intel Xeon, Ryzen, Core i5, Apple M2, Graviton, ...) or the words "CPU
     model not recorded".
  4. README.md's first 30 lines hold `scripts/quickstart.sh` and README's test command: its first
     line that starts with `ctest` (README must have one).
  5. Every reference to a section of the results pages, written as the page's name
     (BENCHMARKS.md or docs/benchmark-history.md), a comma and a heading in double quotes (with or
     without an opening parenthesis, wrapped over comment lines or not), in src/, cli/, docs/,
     scripts/, tests/, bench/, fuzz/, python/ and the top-level *.md files, names a heading of that
     page: the quoted text is a heading's text, or the start of one followed by a non-alphanumeric
     character (so Scale names the heading Scale, and Relative poses names the heading "Relative
     poses: the paper's sampler ablation on real data").
  6. The marker pairs that scripts rewrite between (`<!-- NAME:begin -->` ... `<!-- NAME:end -->`)
     are whole in BENCHMARKS.md and README.md: each begin has its end after it, and the reverse.
"""
import os
import re
import sys

MAX_LINES = 600
WINDOW_ABOVE = 12
WINDOW_BELOW = 6
README_HEAD = 30
REFERENCE_DIRS = ["src", "cli", "docs", "scripts", "tests", "bench", "fuzz", "python"]
REFERENCE_SUFFIXES = (".h", ".hpp", ".cc", ".cpp", ".c", ".py", ".sh", ".md", ".txt", ".cmake",
                      ".js", ".html", ".css", ".in")
PAGES = {"BENCHMARKS.md": "BENCHMARKS.md",
         "docs/benchmark-history.md": os.path.join("docs", "benchmark-history.md")}

HEX_WITH_LETTER_AND_DIGIT = re.compile(
    r"(?<![0-9A-Za-z])(?=[0-9a-f]*[a-f])(?=[0-9a-f]*[0-9])[0-9a-f]{7,40}(?![0-9A-Za-z])")
HEX_AFTER_COMMIT = re.compile(r"\b[Cc]ommits?\s+[0-9a-f]{7,40}(?![0-9A-Za-z])")
CPU_MODEL = re.compile(
    r"AMD EPYC|\bEPYC\b|\bXeon\b|\bIntel\b|\bRyzen\b|Threadripper|\bCore i[3579]\b|"
    r"Apple M[1-9]\b|\bGraviton|\bAmpere\b|\bNeoverse\b|\bPOWER[89]\b|CPU model not recorded")
REFERENCE = re.compile(r"(BENCHMARKS\.md|docs/benchmark-history\.md),\s*\"([^\"]+)\"")
MARKER = re.compile(r"<!--\s*([\w.-]+):(begin|end)\s*-->")


def read_lines(path):
    with open(path, encoding="utf-8") as f:
        return f.read().split("\n")


def is_fence(line):
    return line.lstrip().startswith("```") or line.lstrip().startswith("~~~")


def markdown_structure(lines):
    """(headings, tables): headings as (index, text), tables as (first index, last index), both
    outside fenced code blocks."""
    headings, tables = [], []
    in_fence = False
    table_start = None
    for i, line in enumerate(lines):
        if is_fence(line):
            in_fence = not in_fence
        is_table = not in_fence and line.lstrip().startswith("|")
        if is_table and table_start is None:
            table_start = i
        if not is_table and table_start is not None:
            tables.append((table_start, i - 1))
            table_start = None
        if not in_fence and re.match(r"#{1,6}\s", line):
            headings.append((i, line.lstrip("#").strip().rstrip("#").strip()))
    if table_start is not None:
        tables.append((table_start, len(lines) - 1))
    return headings, tables


def has_commit(text):
    return bool(HEX_WITH_LETTER_AND_DIGIT.search(text) or HEX_AFTER_COMMIT.search(text))


def table_window(lines, heading_lines, first, last):
    above = []
    for i in range(first - 1, max(-1, first - 1 - WINDOW_ABOVE), -1):
        if i in heading_lines:
            break
        above.append(lines[i])
    below = []
    for i in range(last + 1, min(len(lines), last + 1 + WINDOW_BELOW)):
        if i in heading_lines:
            break
        below.append(lines[i])
    return "\n".join(reversed(above)) + "\n" + "\n".join(below)


def heading_paragraph(lines, headings, first):
    """The first block of non-blank lines under the nearest heading above line `first`."""
    above = [index for index, _ in headings if index < first]
    if not above:
        return ""
    block = []
    for line in lines[above[-1] + 1:first]:
        if line.strip():
            block.append(line)
        elif block:
            break
    return "\n".join(block)


def check_benchmarks(source, problems):
    path = os.path.join(source, "BENCHMARKS.md")
    if not os.path.isfile(path):
        problems.append("BENCHMARKS.md: missing")
        return 0, 0
    lines = read_lines(path)
    num_lines = len(lines) - 1 if lines and lines[-1] == "" else len(lines)
    if num_lines > MAX_LINES:
        problems.append(f"BENCHMARKS.md: {num_lines} lines, more than {MAX_LINES}; earlier runs "
                        "and long diagnoses belong in docs/benchmark-history.md")
    headings, tables = markdown_structure(lines)
    heading_lines = {index for index, _ in headings}
    for first, last in tables:
        window = table_window(lines, heading_lines, first, last)
        where = f"BENCHMARKS.md:{first + 1}: the table '{lines[first].strip()[:60]}'"
        if not has_commit(window):
            problems.append(f"{where} names no commit hash within {WINDOW_ABOVE} lines above or "
                            f"{WINDOW_BELOW} below it")
        if not (CPU_MODEL.search(window) or
                CPU_MODEL.search(heading_paragraph(lines, headings, first))):
            problems.append(f"{where} names no CPU model (or 'CPU model not recorded') near it or "
                            "under its section's heading")
    return num_lines, len(tables)


def check_readme(source, problems):
    path = os.path.join(source, "README.md")
    if not os.path.isfile(path):
        problems.append("README.md: missing")
        return
    lines = read_lines(path)
    head = "\n".join(lines[:README_HEAD])
    if "scripts/quickstart.sh" not in head:
        problems.append(f"README.md: its first {README_HEAD} lines lack scripts/quickstart.sh")
    ctest = [i for i, line in enumerate(lines) if line.lstrip().startswith("ctest")]
    if not ctest:
        problems.append("README.md: no test command (a line starting with `ctest`)")
    elif ctest[0] >= README_HEAD:
        problems.append(f"README.md:{ctest[0] + 1}: the test command `{lines[ctest[0]].strip()}` "
                        f"is not in the first {README_HEAD} lines")


def check_markers(source, problems):
    for name in ["BENCHMARKS.md", "README.md"]:
        path = os.path.join(source, name)
        if not os.path.isfile(path):
            continue
        open_markers = {}
        for i, line in enumerate(read_lines(path)):
            for marker, kind in MARKER.findall(line):
                if kind == "begin":
                    if marker in open_markers:
                        problems.append(
                            f"{name}:{i + 1}: <!-- {marker}:begin --> again before its end")
                    open_markers[marker] = i
                elif marker in open_markers:
                    del open_markers[marker]
                else:
                    problems.append(f"{name}:{i + 1}: <!-- {marker}:end --> without its begin")
        for marker, i in open_markers.items():
            problems.append(f"{name}:{i + 1}: <!-- {marker}:begin --> without its end")


def comment_text(lines):
    """The lines joined by single spaces, each without its indentation and comment marker, so that
    a reference wrapped over comment lines reads as one phrase."""
    parts = []
    for line in lines:
        text = line.strip()
        text = re.sub(r"^(///?|/\*+|\*+/?|#+|--)\s?", "", text)
        parts.append(text.strip())
    return " ".join(parts)


def reference_files(source):
    for name in sorted(os.listdir(source)):
        if name.endswith(".md") and os.path.isfile(os.path.join(source, name)):
            yield name
    for folder in REFERENCE_DIRS:
        root = os.path.join(source, folder)
        for directory, subdirs, files in os.walk(root):
            subdirs[:] = sorted(d for d in subdirs if not d.startswith("."))
            for name in sorted(files):
                if name.endswith(REFERENCE_SUFFIXES):
                    yield os.path.relpath(os.path.join(directory, name), source)


def heading_texts(source, page):
    path = os.path.join(source, PAGES[page])
    if not os.path.isfile(path):
        return None
    headings, _ = markdown_structure(read_lines(path))
    return [text for _, text in headings]


def names_heading(reference, headings):
    reference = " ".join(reference.split())
    for heading in headings:
        heading = " ".join(heading.split())
        if heading == reference:
            return True
        if heading.startswith(reference) and not heading[len(reference)].isalnum():
            return True
    return False


def check_references(source, problems):
    headings = {page: heading_texts(source, page) for page in PAGES}
    count = 0
    for relative in reference_files(source):
        try:
            lines = read_lines(os.path.join(source, relative))
        except (UnicodeDecodeError, OSError):
            continue
        for page, reference in REFERENCE.findall(comment_text(lines)):
            count += 1
            if headings[page] is None:
                problems.append(
                    f"{relative}: refers to {page}, \"{reference}\", but {page} is missing")
            elif not names_heading(reference, headings[page]):
                problems.append(f"{relative}: ({page}, \"{reference}\") names no heading of {page}")
    return count


def main(argv):
    if len(argv) != 2 or not os.path.isdir(argv[1]):
        print("usage: check_results_pages.py SOURCE_DIR", file=sys.stderr)
        return 2
    source = argv[1]
    problems = []
    num_lines, num_tables = check_benchmarks(source, problems)
    check_readme(source, problems)
    check_markers(source, problems)
    num_references = check_references(source, problems)
    if problems:
        print(f"check_results_pages: {len(problems)} problem(s) in {source}:")
        for problem in problems:
            print(f"  {problem}")
        return 1
    print(f"check_results_pages: OK: BENCHMARKS.md {num_lines} lines, {num_tables} tables, each "
          f"with a commit and a CPU model, README's set-up in its first {README_HEAD} lines, "
          f"{num_references} section references resolved")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
