#!/usr/bin/env bash
# No include cycle in src/: a unit is a header with its .cpp (core/subdiv/refiner.h + refiner.cpp),
# and unit A depends on unit B when A's header or source includes B's header. A cycle among units
# means none of them can be understood, tested or moved without the others (docs/README.md, "No include cycle").
# Prints every cycle as "a -> b -> ... -> a" with the include line that closes each step.
# Usage: bash include_cycles.sh <polarview-exe> <repo>
set -u
/usr/bin/python3 - "$2/src" <<'PY'
import os, re, sys
src = sys.argv[1]
include = re.compile(r'^\s*#\s*include\s*"([^"]+)"')
edges = {}  # unit -> {unit: "file:line"}
for root, _, files in os.walk(src):
    for name in files:
        if not name.endswith((".h", ".cpp")):
            continue
        path = os.path.join(root, name)
        rel = os.path.relpath(path, src)
        unit = os.path.splitext(rel)[0]
        edges.setdefault(unit, {})
        with open(path, encoding="utf-8") as f:
            for number, line in enumerate(f, 1):
                m = include.match(line)
                if not m or not m.group(1).endswith(".h"):
                    continue
                target = os.path.splitext(m.group(1))[0]
                if target != unit and os.path.exists(os.path.join(src, m.group(1))):
                    edges[unit].setdefault(target, f"src/{rel}:{number}")

# Tarjan's strongly connected components; each component of more than one unit holds a cycle.
index, low, stack, on_stack, components = {}, {}, [], set(), []
def connect(v):
    work = [(v, iter(sorted(edges.get(v, {}))))]
    index[v] = low[v] = len(index)
    stack.append(v); on_stack.add(v)
    while work:
        node, children = work[-1]
        child = next(children, None)
        if child is not None:
            if child not in index:
                index[child] = low[child] = len(index)
                stack.append(child); on_stack.add(child)
                work.append((child, iter(sorted(edges.get(child, {})))))
            elif child in on_stack:
                low[node] = min(low[node], index[child])
            continue
        work.pop()
        if work:
            low[work[-1][0]] = min(low[work[-1][0]], low[node])
        if low[node] == index[node]:
            component = []
            while True:
                w = stack.pop(); on_stack.discard(w); component.append(w)
                if w == node:
                    break
            if len(component) > 1:
                components.append(sorted(component))
for unit in sorted(edges):
    if unit not in index:
        connect(unit)

def cycle_in(component):
    """One cycle through the component's first unit (breadth-first back to it)."""
    members, start = set(component), component[0]
    previous, frontier = {start: None}, [start]
    while frontier:
        following = []
        for u in frontier:
            for w in sorted(edges[u]):
                if w == start:
                    path = [u]
                    while previous[path[-1]] is not None:
                        path.append(previous[path[-1]])
                    return list(reversed(path)) + [start]
                if w in members and w not in previous:
                    previous[w] = u
                    following.append(w)
        frontier = following
    return component

for component in components:
    cycle = cycle_in(component)
    print("FAIL: include cycle " + " -> ".join(cycle))
    for a, b in zip(cycle, cycle[1:]):
        print(f"  {edges[a][b]}: {a} includes {b}.h")
units = len(edges)
if components:
    print(f"include_cycles: {len(components)} cycles among {units} units")
    sys.exit(1)
print(f"include_cycles: ok ({units} units, no cycle)")
PY
