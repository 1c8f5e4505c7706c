#!/usr/bin/env python3
"""Checks that the includes of src/ follow the pipeline order of docs/ARCHITECTURE.md.

Every folder under src/ is one stage of the pipeline. A file may include headers of its own stage
and of earlier stages, never of a later one; and the folders may not include each other in a
cycle. Prints each violation as file:line and exits 1 when there is any, 0 otherwise.

Usage: scripts/check-includes.py [REPO_ROOT]   (default: the folder above this script)
Standard library only; run by ctest as `include_order_check`.
"""
import os
import re
import sys

# The stages, earliest first (derived from the includes and docs/ARCHITECTURE.md's diagram).
STAGES = [
    "util",        # timing, hashes, bulk files, InputError, CHECK: used everywhere
    "geometry",    # vectors, planes, convex polygons/polyhedra, exact predicates, tolerances
    "scene",       # Scene/Patch/Material, OBJ and Assimp importers, face -> patches
    "generators",  # built-in scenes
    "quake",       # Quake .map level sources and .prt portal files as input
    "input",       # loadScene: the dispatch by extension over the importers above
    "bsp",         # §3: BSP, cells, portals
    "raycast",     # Embree ray oracle (used by visibility's verify and by radiosity)
    "visibility",  # §4-§5: cell and patch visibility, blocker lists
    "linespace",   # §6.1-§6.3: tubes, blocker classification
    "radiosity",   # §6, HSA91: hierarchical radiosity
    "render",      # pictures of a solution
    "report",      # viewer and report pages
    "cli",         # the globalvis front end: composes everything
]

# Files that live in one folder but belong to another stage. Each entry is printed on every run,
# so the exception cannot be forgotten.
# None today: the last one, src/quake/leaf_pvs.*, became visibility/cell_pvs.* (issue #16).
KNOWN_EXCEPTIONS = {}

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def stage_of(rel):
    """The stage of a path relative to src/ ("bsp/portals.h"), or None outside the stages."""
    if rel in KNOWN_EXCEPTIONS:
        return KNOWN_EXCEPTIONS[rel]
    folder = rel.split("/", 1)[0]
    return folder if folder in STAGES else None


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..")
    src = os.path.join(os.path.abspath(root), "src")
    rank = {name: i for i, name in enumerate(STAGES)}
    errors = []
    edges = {}  # (from stage, to stage) -> first "file:line" that makes it

    for rel in sorted(KNOWN_EXCEPTIONS):
        gone = "" if os.path.exists(os.path.join(src, rel)) else " (file gone: drop the entry)"
        print(f"known exception: src/{rel} counted as stage '{KNOWN_EXCEPTIONS[rel]}'{gone}")

    for folder in sorted(os.listdir(src)):
        if not os.path.isdir(os.path.join(src, folder)):
            continue
        if folder not in rank:
            errors.append(f"src/{folder}/: folder is not a stage of scripts/check-includes.py")
            continue
        for dirpath, _, files in os.walk(os.path.join(src, folder)):
            for name in sorted(files):
                if not name.endswith((".h", ".cpp")):
                    continue
                path = os.path.join(dirpath, name)
                rel = os.path.relpath(path, src).replace(os.sep, "/")
                here = stage_of(rel)
                with open(path, encoding="utf-8") as f:
                    for number, line in enumerate(f, 1):
                        m = INCLUDE.match(line)
                        if not m:
                            continue
                        there = stage_of(m.group(1))
                        if there is None:
                            continue  # a header outside src/ (none today) or a system one
                        where = f"src/{rel}:{number}"
                        if rank[there] > rank[here]:
                            errors.append(f"{where}: {here} includes {m.group(1)} of the later "
                                          f"stage {there}")
                        if there != here:
                            edges.setdefault((here, there), where)

    # Cycles between stages (possible only through the exceptions if the order check passes, but
    # checked on its own so a reordering of STAGES cannot hide one).
    graph = {}
    for (a, b) in edges:
        graph.setdefault(a, set()).add(b)
    state = {}

    def visit(node, trail):
        state[node] = "open"
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == "open":
                cycle = trail[trail.index(nxt):] + [nxt] if nxt in trail else [node, nxt]
                hops = ", ".join(f"{x} -> {y} ({edges[(x, y)]})" for x, y in zip(cycle, cycle[1:]))
                errors.append(f"cycle between stages: {hops}")
            elif nxt not in state:
                visit(nxt, trail + [nxt])
        state[node] = "done"

    for node in sorted(graph):
        if node not in state:
            visit(node, [node])

    for e in errors:
        print(e)
    if errors:
        print(f"check-includes: {len(errors)} problem(s); the order is in scripts/check-includes.py "
              "and docs/ARCHITECTURE.md")
        return 1
    print(f"check-includes: OK ({len(edges)} stage-to-stage dependencies, all earlier)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
