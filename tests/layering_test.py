#!/usr/bin/env python3
"""The layering of the code (docs/development.md, "Map of the code"), checked on every include.

1. Top-level folders form a stack: base < lcmtypes < bus < modules < sim < evolver < tools. A file
   includes only from its own folder or lower ones (tests include anything).
2. Roles within a component: a pure core (modules/core, sim/core, evolver/ga, evolver/store,
   evolver/evolve) includes no bus, no LCM, no node and no app; a node (modules/node, sim/node,
   evolver/fitness, evolver/farm, evolver/arena) includes no app.
3. A main (an `app` folder, tools/<tool>) is included by nobody but itself.
Prints every break as FILE:LINE: what, and exits 1 when there is one.
"""
import pathlib
import re
import sys

root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".")
stack = ["base", "lcmtypes", "bus", "modules", "sim", "evolver", "tools"]
cores = {"modules/core", "sim/core", "evolver/ga", "evolver/store", "evolver/evolve"}
nodes = {"modules/node", "sim/node", "evolver/fitness", "evolver/farm", "evolver/arena"}
include = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')

def role(path):  # "sim/core" for sim/core/x.cc
    parts = pathlib.PurePosixPath(path).parts
    return "/".join(parts[:2]) if len(parts) > 2 else parts[0]

def is_main(folder):
    return folder.endswith("/app") or (folder.startswith("tools/") and folder != "tools")

breaks = []
for top in stack:
    for f in sorted((root / top).rglob("*")):
        if f.suffix not in (".h", ".cc", ".hpp", ".cpp"):
            continue
        rel = f.relative_to(root).as_posix()
        mine = role(rel)
        for n, line in enumerate(f.read_text(errors="replace").splitlines(), 1):
            m = include.match(line)
            if not m:
                continue
            quote, target = m.groups()
            where = f"{rel}:{n}: "
            if quote == "<":
                if mine in cores and (target.startswith("ahhs/") or target.startswith("lcm/")):
                    breaks.append(where + f"the core {mine} includes LCM <{target}>")
                continue
            first = target.split("/")[0]
            if first not in stack:
                continue
            if stack.index(first) > stack.index(top):
                breaks.append(where + f"{top}/ includes the higher layer {target}")
            theirs = role(target)
            if mine in cores and (first == "bus" or theirs in nodes or is_main(theirs)):
                breaks.append(where + f"the core {mine} includes {target}")
            if mine in nodes and is_main(theirs):
                breaks.append(where + f"the node {mine} includes the main {target}")
            if is_main(theirs) and theirs != mine:
                breaks.append(where + f"{mine} includes another program's main {target}")

for b in breaks:
    print(b)
if breaks:
    sys.exit(1)
print("layering: every include goes down the stack")
