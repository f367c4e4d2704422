#!/usr/bin/env python3
"""Fails when the includes of src/ramap break its layers (docs/architecture.md, "Layers"):

  - a file includes one of a layer above its own;
  - files include each other in a circle (a.cc includes b.h, which includes a.h), within a folder
    or across folders: a file and its header count as one module, so mapper.cc including
    calibration_passes.h while calibration_passes.cc includes mapper.h is a circle.

    check_layers.py [SOURCE_DIR]
"""

import pathlib
import re
import sys

LAYERS = ["util", "scene", "geometry", "graph", "synthetic", "averaging", "refine", "eval", "io",
          "features", "report", "estimators", "mapper", "jobs", "compare"]
RANK = {layer: k for k, layer in enumerate(LAYERS)}
INCLUDE = re.compile(r'#include "ramap/([\w/]+)\.(?:h|cc)"')


def module_of(path, root):
    """"mapper/mapper" for src/ramap/mapper/mapper.cc and .h."""
    return str(path.relative_to(root).with_suffix(""))


def circles(graph):
    """The strongly connected components of more than one module (Tarjan's algorithm)."""
    index, low, on_stack, stack, found = {}, {}, set(), [], []
    counter = [0]

    def visit(node):
        index[node] = low[node] = counter[0]
        counter[0] += 1
        stack.append(node)
        on_stack.add(node)
        for target in graph.get(node, ()):
            if target not in index:
                visit(target)
                low[node] = min(low[node], low[target])
            elif target in on_stack:
                low[node] = min(low[node], index[target])
        if low[node] == index[node]:
            component = []
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.append(member)
                if member == node:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    sys.setrecursionlimit(10000)
    for node in sorted(graph):
        if node not in index:
            visit(node)
    return found


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".") / "src" / "ramap"
    problems = []
    graph = {}
    for path in sorted(root.rglob("*")):
        if path.suffix not in (".h", ".cc"):
            continue
        layer = path.relative_to(root).parts[0]
        if layer not in RANK:
            problems.append(f"{path}: folder '{layer}' is in no layer (scripts/check_layers.py)")
            continue
        module = module_of(path, root)
        for number, line in enumerate(path.read_text().splitlines(), 1):
            match = INCLUDE.match(line)
            if not match:
                continue
            target = match.group(1)
            target_layer = target.split("/")[0]
            if target_layer in RANK and RANK[target_layer] > RANK[layer]:
                problems.append(f"{path}:{number}: {layer} includes {target_layer}")
            if target != module:
                graph.setdefault(module, set()).add(target)
    for component in circles(graph):
        problems.append("include circle: " + " <-> ".join(component))
    if problems:
        print("\n".join(problems))
        sys.exit(1)
    print(f"check_layers: no include runs up a layer and no files include each other in a circle "
          f"({len(graph)} modules under {root})")


if __name__ == "__main__":
    main()
