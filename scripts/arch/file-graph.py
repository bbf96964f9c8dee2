#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The files of src/ as a graph, and its circles.

Every translation unit of the build (compile_commands.json) is compiled
again at -O0 with gcc's -fcallgraph-info, which writes each function
defined and each call with the place of the call.  A file points to
another when it includes it (a project header) or when a call written in
it (in a .c file or in an inline function of a header) goes to a function
defined in the other.  A header and the .c file of the same name are one
node (a module: its declarations and their definitions).  Calls through
pointers (ops tables, callbacks) are not edges: they are how a lower layer
hands work up without knowing who does it.

A circle is a strongly connected component of more than one node: files
that reach each other by includes and calls.

The build must have been built (the LCM types are generated headers).
Configure it with -DSW_MPI=ON to see the MPI files too.

    scripts/arch/file-graph.py [BUILD]        circles, one per line (exit 1 if any)
    scripts/arch/file-graph.py BUILD --edges  every edge, "from -> to (why)"
"""
import json, os, re, shlex, subprocess, sys, tempfile

top = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
build = sys.argv[1] if len(sys.argv) > 1 and not sys.argv[1].startswith("-") else "build"
build = os.path.join(top, build) if not os.path.isabs(build) else build
show_edges = "--edges" in sys.argv
src = os.path.join(top, "src")
inc = os.path.join(top, "include")


def ours(path):
    p = os.path.realpath(path)
    return p.startswith(src + os.sep) or p.startswith(inc + os.sep)


def node(path):
    """The module of a file: its path under the top without the extension;
    public headers (include/swaywatch/X.h) are their own modules."""
    rel = os.path.relpath(os.path.realpath(path), top)
    return os.path.splitext(rel)[0]


cmds = json.load(open(os.path.join(build, "compile_commands.json")))
tus = [c for c in cmds if ours(c["file"]) and c["file"].endswith(".c")]
edges = {}  # (a, b) -> why


def add(a, b, why):
    if a != b:
        edges.setdefault((a, b), why)


defined = {}  # function -> set of modules defining it (extern ones)
per_tu = []
with tempfile.TemporaryDirectory() as tmp:
    for i, c in enumerate(tus):
        args = shlex.split(c["command"]) if "command" in c else list(c["arguments"])
        out = os.path.join(tmp, "tu%d.o" % i)
        a2 = []
        skip = False
        for a in args:
            if skip:
                skip = False
                continue
            if a == "-o":
                skip = True
                continue
            if re.match(r"^-O", a) or a in ("-Werror", "-flto"):
                continue
            a2.append(a)
        a2 += ["-O0", "-fcallgraph-info", "-o", out, "-w"]
        subprocess.run(a2, cwd=c["directory"], check=True)
        ci = open(os.path.splitext(out)[0] + ".ci").read()
        nodes, calls = {}, []
        for m in re.finditer(r'node: \{ title: "([^"]+)" label: "[^\\]*\\n([^:"]+):\d+:\d+"( shape : ellipse)?', ci):
            name, loc, ext = m.group(1), m.group(2), m.group(3)
            if not ext:
                nodes[name] = os.path.join(c["directory"], loc)
        for m in re.finditer(r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)" label: "([^:"]+):\d+', ci):
            calls.append((m.group(1), m.group(2), os.path.join(c["directory"], m.group(3))))
        for name, loc in nodes.items():
            if ours(loc) and name != "__indirect_call":
                defined.setdefault(name, set()).add(node(loc))
        per_tu.append((c["file"], nodes, calls))
        # includes: the TU's own dependency list, project headers only
        dep = subprocess.run([x for x in a2 if x != "-fcallgraph-info"][:-4] +
                             ["-w", "-E", "-H", "-o", "/dev/null"],
                             cwd=c["directory"], capture_output=True, text=True).stderr
        stack = [c["file"]]
        for line in dep.splitlines():
            m = re.match(r"^(\.+) (.*)$", line)
            if not m:
                continue
            depth, hdr = len(m.group(1)), m.group(2)
            hdr = os.path.join(c["directory"], hdr)
            del stack[depth:]
            if ours(hdr) and ours(stack[-1]):
                add(node(stack[-1]), node(hdr), "includes")
            stack.append(hdr)

for tu, nodes, calls in per_tu:
    for caller, callee, site in calls:
        if not ours(site) or callee == "__indirect_call":  # gcc's name for a call through a pointer
            continue
        if callee in nodes and ours(nodes[callee]):
            targets = {node(nodes[callee])}
        else:
            targets = defined.get(callee, set())
        for t in targets:
            add(node(site), t, "calls %s" % callee)

# Tarjan's strongly connected components
graph = {}
for (a, b) in edges:
    graph.setdefault(a, set()).add(b)
    graph.setdefault(b, set())
index, low, onstack, stack, sccs, counter = {}, {}, set(), [], [], [0]
sys.setrecursionlimit(10000)


def strong(v):
    index[v] = low[v] = counter[0]
    counter[0] += 1
    stack.append(v)
    onstack.add(v)
    for w in graph[v]:
        if w not in index:
            strong(w)
            low[v] = min(low[v], low[w])
        elif w in onstack:
            low[v] = min(low[v], index[w])
    if low[v] == index[v]:
        comp = []
        while True:
            w = stack.pop()
            onstack.discard(w)
            comp.append(w)
            if w == v:
                break
        sccs.append(comp)


for v in sorted(graph):
    if v not in index:
        strong(v)

if show_edges:
    for (a, b), why in sorted(edges.items()):
        print("%s -> %s (%s)" % (a, b, why))
circles = [sorted(c) for c in sccs if len(c) > 1]
for c in sorted(circles):
    inside = ["%s -> %s (%s)" % (a, b, w) for (a, b), w in sorted(edges.items())
              if a in c and b in c]
    print("circle: " + ", ".join(c))
    for e in inside:
        print("    " + e)
print("%d modules, %d edges, %d circles" % (len(graph), len(edges), len(circles)), file=sys.stderr)
sys.exit(1 if circles else 0)
