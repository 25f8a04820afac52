#!/usr/bin/env python3
"""Reports spectrace's structure as issue 26 measures it: the import graph between top-level
modules of `src/` (an edge A → B when a file under src/A names `crate::B`), its cycles, the
render-side modules that import `loader`, files over 400 lines and functions over 120 lines.

    python3 scripts/arch_report.py [--strict]

How it counts: every `crate::NAME` path in a file's code (comments and strings stripped) is an
edge from the file's top-level module to NAME (`use crate::{a, b}` counts each); `super::` is
inside one module and never an edge. Cycles are the strongly connected components of more than
one module (Tarjan). A function's length runs from its `fn` line to the line of its closing
brace (braces in strings and comments ignored). `--strict` exits 1 if any count is non-zero.
"""

from __future__ import annotations

import re
import sys
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SRC = ROOT / "src"
RENDER_SIDE = ["film", "integrator", "light", "material", "geometry", "render", "scene"]


def strip(text: str) -> str:
    """The text with comments, string and char literals blanked (newlines kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "r" and re.match(r'r#*"', text[i:i + 10]) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'r(#*)"', text[i:])
            end = '"' + m.group(1)
            j = text.find(end, i + len(m.group(0)))
            j = n if j < 0 else j + len(end)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "'" and re.match(r"'(\\.|[^\\'])'", text[i:i + 4]):
            m = re.match(r"'(\\.|[^\\'])'", text[i:])
            out.append(" " * len(m.group(0)))
            i += len(m.group(0))
        else:
            out.append(c)
            i += 1
    return "".join(out)


def top_module(path: Path) -> str:
    rel = path.relative_to(SRC)
    return rel.parts[0].removesuffix(".rs") if len(rel.parts) > 1 else rel.stem


def crate_refs(code: str) -> set[str]:
    refs = set(re.findall(r"\bcrate::([a-z_][a-z0-9_]*)", code))
    for group in re.findall(r"\bcrate::\{([^}]*)\}", code):
        refs.update(re.findall(r"(?:^|,)\s*([a-z_][a-z0-9_]*)", group))
    return refs


def functions(code: str) -> list[tuple[str, int, int]]:
    """(name, first line, length in lines) of every fn with a body."""
    res = []
    for m in re.finditer(r"\bfn\s+([A-Za-z_][A-Za-z0-9_]*)", code):
        i = m.end()
        depth = 0
        # find the body's opening brace before any ';' at depth 0 (a declaration)
        while i < len(code):
            ch = code[i]
            if ch in "(<[":
                depth += 1
            elif ch in ")>]":
                depth -= 1
            elif ch == ";" and depth <= 0:
                i = -1
                break
            elif ch == "{" and depth <= 0:
                break
            i += 1
        if i < 0 or i >= len(code):
            continue
        start = code.count("\n", 0, m.start()) + 1
        depth, j = 0, i
        while j < len(code):
            if code[j] == "{":
                depth += 1
            elif code[j] == "}":
                depth -= 1
                if depth == 0:
                    break
            j += 1
        end = code.count("\n", 0, j) + 1
        res.append((m.group(1), start, end - start + 1))
    return res


def sccs(graph: dict[str, set[str]]) -> list[list[str]]:
    index, low, on, stack, out = {}, {}, set(), [], []
    counter = [0]

    def visit(v: str) -> None:
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def main() -> int:
    strict = "--strict" in sys.argv
    modules = {top_module(p) for p in SRC.rglob("*.rs")}
    graph: dict[str, set[str]] = defaultdict(set)
    why: dict[tuple[str, str], list[str]] = defaultdict(list)
    long_files, long_fns = [], []
    for p in sorted(SRC.rglob("*.rs")):
        text = p.read_text()
        code = strip(text)
        # test modules are not part of the layering
        cut = re.search(r"#\[cfg\(test\)\]\s*mod\s+tests", code)
        body = code[: cut.start()] if cut else code
        a = top_module(p)
        for b in crate_refs(body):
            if b in modules and b != a:
                graph[a].add(b)
                why[(a, b)].append(str(p.relative_to(ROOT)))
        n = text.count("\n")
        if n > 400:
            long_files.append((n, str(p.relative_to(ROOT))))
        for name, line, length in functions(code):
            if length > 120:
                long_fns.append((length, f"{p.relative_to(ROOT)}:{line} {name}"))
    cycles = sccs(graph)
    print(f"top-level modules: {len(modules)}; import edges: {sum(len(v) for v in graph.values())}")
    print(f"import cycles (strongly connected groups of modules): {len(cycles)}")
    for c in cycles:
        print("  " + " ↔ ".join(c))
        for a in c:
            for b in sorted(graph[a] & set(c)):
                print(f"    {a} → {b}: {', '.join(sorted(set(why[(a, b)]))[:4])}")
    render_loader = [(m, sorted(set(why[(m, 'loader')]))) for m in RENDER_SIDE if "loader" in graph[m]]
    print(f"render-side modules importing loader: {len(render_loader)}")
    for m, files in render_loader:
        print(f"  {m}: {', '.join(files[:6])}{' …' if len(files) > 6 else ''}")
    print(f"files over 400 lines: {len(long_files)}")
    for n, f in sorted(long_files, reverse=True):
        print(f"  {n:5d} {f}")
    print(f"functions over 120 lines: {len(long_fns)}")
    for n, f in sorted(long_fns, reverse=True):
        print(f"  {n:5d} {f}")
    bad = len(cycles) + len(render_loader) + len(long_files) + len(long_fns)
    return 1 if strict and bad else 0


if __name__ == "__main__":
    sys.exit(main())
