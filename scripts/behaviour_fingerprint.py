#!/usr/bin/env python3
"""What a run produced, as text two runs can be diffed by: used by scripts/reproduce_behaviour.sh.

    behaviour_fingerprint.py summary SUMMARY_JSON WORK_DIR   every key of summary.json, one line
                                                            each ("a.b[2].c = value"), the keys
                                                            that measure time or memory left out
    behaviour_fingerprint.py models OUTPUT_DIR              the md5 of every model file under it
    behaviour_fingerprint.py evaluation JSON [WORK_DIR]     any other JSON (an evaluation), every
                                                            key but the volatile ones

Paths under WORK_DIR are written as $WORK, so that two runs in different folders compare equal.
"""

import hashlib
import json
import pathlib
import re
import sys

# Keys whose values are measurements of the machine (seconds, memory) or of when and by what
# binary the run was made: they differ between two runs of the same code.
VOLATILE = re.compile(r"(seconds|_s$|^peak_rss|_mib$|^version$|^commit$|^date$|^ramap_version$"
                      r"|^started$|^finished$|^timestamp$)")


def flatten(value, prefix, out):
    if isinstance(value, dict):
        for key in sorted(value):
            if VOLATILE.search(key):
                continue
            flatten(value[key], f"{prefix}.{key}" if prefix else key, out)
    elif isinstance(value, list):
        for index, item in enumerate(value):
            flatten(item, f"{prefix}[{index}]", out)
    else:
        out.append(f"{prefix} = {json.dumps(value)}")


def json_lines(path, work_dir):
    text = pathlib.Path(path).read_text()
    if work_dir:
        text = text.replace(str(pathlib.Path(work_dir).resolve()), "$WORK")
        text = text.replace(str(work_dir), "$WORK")
    lines = []
    flatten(json.loads(text), "", lines)
    return lines


def models(output_dir):
    lines = []
    root = pathlib.Path(output_dir)
    for path in sorted(root.rglob("*")):
        if path.is_file() and path.suffix in (".bin", ".txt") and path.name != "log.txt":
            digest = hashlib.md5(path.read_bytes()).hexdigest()
            lines.append(f"{path.relative_to(root)} {digest}")
    return lines


def main():
    kind = sys.argv[1]
    if kind in ("summary", "evaluation"):
        lines = json_lines(sys.argv[2], sys.argv[3] if len(sys.argv) > 3 else "")
    elif kind == "models":
        lines = models(sys.argv[2])
    else:
        sys.exit(f"behaviour_fingerprint.py: unknown kind '{kind}' (summary, models, evaluation)")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
