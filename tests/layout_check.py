#!/usr/bin/python3
"""The layout of the sources, by what each file includes and calls (issue 17):

  layout_check.py [--root DIR] [--max-lines 800]

  * call circles between files: file A calls a function defined in file B, which (through other files) calls back into
    A; found from the function definitions and calls of every C file of src/ (a call through an ops table or a
    function pointer is no call here: that is how an implementation is reached without a circle)
  * include circles between headers (#include "..." of src/ and include/)
  * files over --max-lines lines in src/, include/, examples/ and python/

Prints what it finds (each circle with one call per step) and the counts; exit status 0 when there is nothing.
"""
import argparse
import glob
import os
import re
import sys

KEYWORDS = {"if", "for", "while", "switch", "return", "sizeof", "do", "else", "case", "defined", "PetscFunctionReturn"}
DEFINITION = re.compile(r"^(?!\s)(?:static\s+|inline\s+|PETSC_EXTERN\s+|PETSC_INTERN\s+)*[A-Za-z_][\w\s\*]*?\b([A-Za-z_]\w*)\s*\(([^;{}]*)\)\s*\{", re.M)
CALL = re.compile(r"\b([A-Za-z_]\w*)\s*\(")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def strip(text):
    """The C text without comments, strings and character constants (their lengths kept by spaces)"""
    pattern = re.compile(r'/\*.*?\*/|//[^\n]*|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'', re.S)
    return pattern.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), text)


def bodies(text):
    """(name, static, body) for each function defined in the stripped text"""
    out = []
    for m in DEFINITION.finditer(text):
        start, depth, k = m.end() - 1, 0, m.end() - 1
        while k < len(text):
            depth += {"{": 1, "}": -1}.get(text[k], 0)
            if depth == 0:
                break
            k += 1
        out.append((m.group(1), text[m.start():m.start(1)].lstrip().startswith("static"), text[start:k + 1]))
    return out


def call_graph(root):
    """{file: {other file: (caller, callee)}} for the C files of src/"""
    files = sorted(glob.glob(os.path.join(root, "src", "**", "*.c"), recursive=True))
    defined, calls = {}, {}
    for path in files:
        text = strip(open(path).read())
        found = bodies(text)
        calls[path] = found
        for name, static, _ in found:
            if not static:
                defined.setdefault(name, path)
    edges = {path: {} for path in files}
    for path, found in calls.items():
        local = {name for name, _, _ in found}
        for caller, _, body in found:
            for callee in CALL.findall(body):
                if callee in KEYWORDS or callee in local or callee not in defined or defined[callee] == path:
                    continue
                edges[path].setdefault(defined[callee], (caller, callee))
    return edges


def include_graph(root):
    """{header or source: {included file: (line, )}} for #include "..." in src/ and include/"""
    files = sorted(glob.glob(os.path.join(root, "src", "**", "*.[ch]"), recursive=True) + glob.glob(os.path.join(root, "include", "*.h")))
    edges = {}
    for path in files:
        edges[path] = {}
        for name in INCLUDE.findall(open(path).read()):
            target = os.path.normpath(os.path.join(os.path.dirname(path), name))
            if not os.path.exists(target):
                target = os.path.join(root, "include", name)
            if os.path.exists(target):
                edges[path][target] = (name,)
    return edges


def circles(edges):
    """The strongly connected components of more than one node (Tarjan), each as a cycle through them"""
    index, low, stack, on, found, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges.get(v, {}):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(cycle_in(edges, set(component)))

    sys.setrecursionlimit(10000)
    for v in sorted(edges):
        if v not in index:
            visit(v)
    return found


def cycle_in(edges, component):
    """One cycle through the first file of a component: a shortest path back to it (breadth first)"""
    start = min(component)
    previous, frontier = {start: None}, [start]
    while frontier:
        nxt = []
        for v in frontier:
            for w in sorted(edges[v]):
                if w == start:
                    path = [v]
                    while previous[path[-1]] is not None:
                        path.append(previous[path[-1]])
                    return list(reversed(path)) + [start]
                if w in component and w not in previous:
                    previous[w] = v
                    nxt.append(w)
        frontier = nxt
    return [start]


def long_files(root, limit):
    found = []
    for folder, patterns in (("src", ("**/*.c", "**/*.h")), ("include", ("*.h",)), ("examples", ("*.c", "*.py")), ("python", ("**/*.py",))):
        for pattern in patterns:
            for path in glob.glob(os.path.join(root, folder, pattern), recursive=True):
                n = sum(1 for _ in open(path))
                if n > limit:
                    found.append((path, n))
    return sorted(found)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--root", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    parser.add_argument("--max-lines", type=int, default=800)
    args = parser.parse_args()
    rel = lambda p: os.path.relpath(p, args.root)
    calls, includes = call_graph(args.root), include_graph(args.root)
    call_circles, include_circles = circles(calls), circles(includes)
    for cycle in call_circles:
        steps = ["%s (%s calls %s)" % (rel(a), *calls[a][b]) for a, b in zip(cycle, cycle[1:])]
        print("call circle: " + " -> ".join(steps) + " -> " + rel(cycle[-1]))
    for cycle in include_circles:
        print("include circle: " + " -> ".join(rel(f) for f in cycle))
    long = long_files(args.root, args.max_lines)
    for path, n in long:
        print("over %d lines: %s (%d)" % (args.max_lines, rel(path), n))
    nfiles = len(calls)
    nedges = sum(len(v) for v in calls.values())
    print("%d C files of src/, %d calls between files: %d call circles, %d include circles, %d files over %d lines" % (
        nfiles, nedges, len(call_circles), len(include_circles), len(long), args.max_lines))
    sys.exit(1 if call_circles or include_circles or long else 0)


if __name__ == "__main__":
    main()
