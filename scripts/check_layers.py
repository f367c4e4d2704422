#!/usr/bin/env python3
"""Fails when a file of src/ramap includes one of a layer above its own (README, "Layout")."""

import pathlib
import re
import sys

LAYERS = ["util", "scene", "geometry", "synthetic", "graph", "averaging", "refine", "eval", "io",
          "features", "report", "pipeline", "compare"]
RANK = {layer: k for k, layer in enumerate(LAYERS)}

root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".") / "src" / "ramap"
upward = []
for path in sorted(root.rglob("*")):
    if path.suffix not in (".h", ".cc"):
        continue
    layer = path.relative_to(root).parts[0]
    for number, line in enumerate(path.read_text().splitlines(), 1):
        match = re.match(r'#include "ramap/(\w+)/', line)
        if match and RANK[match.group(1)] > RANK[layer]:
            upward.append(f"{path}:{number}: {layer} includes {match.group(1)}")
print("\n".join(upward) if upward else f"check_layers: no include runs up a layer ({root})")
sys.exit(1 if upward else 0)
