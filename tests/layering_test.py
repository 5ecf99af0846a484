#!/usr/bin/env python3
"""The layering of the code (docs/development.md, "Map of the code"), checked on every include.

1. Top-level folders form a stack: base < lcmtypes < bus < modules < sim < episode < evolver <
   tools. A file includes only from its own folder or lower ones (tests include anything).
2. Roles within a component: a pure core (modules/core, sim/core, evolver/ga, evolver/store,
   evolver/evolve) includes no bus, no LCM, no node and no app; a node (modules/node, sim/node,
   episode/fitness, episode/arena, evolver/farm, evolver/run) includes no app.
3. A main (an `app` folder, tools/<tool>) is included by nobody but itself.
4. The CMake link graph follows the same stack: a target defined in a folder's CMakeLists.txt
   links only targets of its own folder or lower ones, and a core's library links no bus, no LCM
   and no node library.
5. The Python analysis (tools/report) imports its own modules without a cycle.
Prints every break as FILE:LINE: what, and exits 1 when there is one.
"""
import pathlib
import re
import sys

root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".")
stack = ["base", "lcmtypes", "bus", "modules", "sim", "episode", "evolver", "tools"]
cores = {"modules/core", "sim/core", "evolver/ga", "evolver/store", "evolver/evolve"}
nodes = {"modules/node", "sim/node", "episode/fitness", "episode/arena", "evolver/farm",
         "evolver/run"}
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

# 4. The link graph: every add_library/add_executable of a stack folder's CMakeLists.txt files,
# its folder (and role, from its first source), and what target_link_libraries gives it.
command = re.compile(r"\b(add_library|add_executable|target_link_libraries)\s*\(([^)]*)\)", re.S)
targets = {}  # name -> (top folder, role, file, line)
links = []  # (file, line, target, [linked names])
for top in stack:
    for cm in sorted((root / top).rglob("CMakeLists.txt")):
        text = cm.read_text(errors="replace")
        text_nc = re.sub(r"#[^\n]*", "", text)
        folder = cm.parent.relative_to(root).as_posix()
        for m in command.finditer(text_nc):
            words = m.group(2).split()
            line = text_nc.count("\n", 0, m.start()) + 1
            where = (cm.relative_to(root).as_posix(), line)
            if not words:
                continue
            if m.group(1) == "target_link_libraries":
                links.append((*where, words[0], [w for w in words[1:] if w not in
                                                 ("PUBLIC", "PRIVATE", "INTERFACE")]))
                continue
            sources = [w for w in words[1:] if w.endswith((".cc", ".cpp", ".c"))]
            src_role = role(f"{folder}/{sources[0]}") if sources else folder
            targets[words[0]] = (top, src_role, *where)
lcm_libs = {"PkgConfig::LCM", "ahhs_bus", "ahhs_lcmtypes"}
for file, line, target, linked in links:
    if target not in targets:
        continue
    top, mine = targets[target][0], targets[target][1]
    for name in linked:
        where = f"{file}:{line}: "
        if mine in cores and (name in lcm_libs or (name in targets and targets[name][1] in nodes)):
            breaks.append(where + f"the core {mine} target {target} links {name}")
        if name not in targets:
            continue
        theirs = targets[name][0]
        if stack.index(theirs) > stack.index(top):
            breaks.append(where + f"{target} ({top}/) links {name} of the higher layer {theirs}/")

# 5. The Python analysis: no import cycle among tools/report's own modules.
report = root / "tools" / "report"
own = {f.stem: f for f in report.glob("*.py")} if report.is_dir() else {}
py_import = re.compile(r"^\s*(?:import\s+(\w+)|from\s+(\w+)\s+import)", re.M)
graph = {name: {a or b for a, b in py_import.findall(f.read_text(errors="replace"))} & set(own)
         for name, f in own.items()}
state = {}
def visit(name, path):
    state[name] = "open"
    for dep in sorted(graph[name]):
        if state.get(dep) == "open":
            cycle = path[path.index(dep):] + [dep] if dep in path else [name, dep]
            breaks.append(f"tools/report/{name}.py:1: import cycle " + " -> ".join(cycle))
        elif dep not in state:
            visit(dep, path + [dep])
    state[name] = "done"
for name in sorted(graph):
    if name not in state:
        visit(name, [name])

for b in breaks:
    print(b)
if breaks:
    sys.exit(1)
print("layering: every include, link and Python import goes down the stack")
