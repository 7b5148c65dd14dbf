#!/usr/bin/env python3
"""Check that the source folders form layers: a file may include headers of its own folder and of
the folders below it, never above (docs/developer-guide.md, "Layers").

The layers, bottom to top:

  util       configuration, option readers, profiling scopes, JSON helpers: no physics
  materials  constitutive laws of the continuum and of the membranes, their Newton tangents
  core       grid, particles, shapes, transfers: the kernels of one MPM step
  contact    what couples bodies on the grid: stacked-body contact, chains, the colour interface
  model      Simulation (settings, state, scratch), geometry, balance, design answers, checks
  io         HDF5 + XDMF, checkpoints, summaries, chain profiles
  step       the explicit step as named phases and its hooks; the stress update
  solvers    equilibrium solvers (dynamic relaxation, Newton) and the stage loop
  scenes     scenes (problem set-ups) and their closed forms
  app        main

A file's layer is its first folder under src/ or include/pmpm/; a file directly in src/ or
include/pmpm/ is a violation too (every file sits in a layer). Before the repository, the script
checks a small synthetic tree with one upward include and one file outside the layers, and fails
if it does not find both, so it cannot pass by finding nothing.

  python3 scripts/layers.py [REPO_ROOT]   # violations, one per line; exit 1 if any
  python3 scripts/layers.py --graph       # also the folder graph (which layer includes which)
"""
import os
import re
import sys
import tempfile

LAYERS = ["util", "materials", "core", "contact", "model", "io", "step", "solvers", "scenes",
          "app"]
RANK = {name: i for i, name in enumerate(LAYERS)}
INCLUDE = re.compile(r'^\s*#\s*include\s+"pmpm/([^"]+)"', re.M)


def layer_of(rel):
    """rel: a path relative to src/ or include/pmpm/; its first folder (None at the top)."""
    parts = rel.split("/")
    return parts[0] if len(parts) > 1 else None


def check(root):
    """(violations, folder graph, files) of the tree at root."""
    bad, graph, files = [], {}, 0
    for base in ("src", os.path.join("include", "pmpm")):
        top = os.path.join(root, base)
        for d, _, names in os.walk(top):
            for n in sorted(names):
                if not n.endswith((".cpp", ".hpp")):
                    continue
                files += 1
                path = os.path.join(d, n)
                rel = os.path.relpath(path, top).replace(os.sep, "/")
                me = layer_of(rel)
                where = os.path.join(base, rel)
                if me not in RANK:
                    bad.append(f"{where}: not in a layer folder ({', '.join(LAYERS)})")
                    continue
                with open(path, encoding="utf-8") as f:
                    text = f.read()
                for inc in INCLUDE.findall(text):
                    other = layer_of(inc)
                    if other not in RANK:
                        bad.append(f"{where}: includes pmpm/{inc}, which is in no layer")
                        continue
                    graph.setdefault(me, set()).add(other)
                    if RANK[other] > RANK[me]:
                        bad.append(f"{where} ({me}) includes pmpm/{inc} ({other}), a layer above")
    return bad, graph, files


def self_check():
    """A synthetic tree with two planted violations must give exactly those two."""
    with tempfile.TemporaryDirectory() as t:
        def put(rel, text):
            p = os.path.join(t, rel)
            os.makedirs(os.path.dirname(p), exist_ok=True)
            with open(p, "w") as f:
                f.write(text)
        put("include/pmpm/util/a.hpp", "#pragma once\n")
        put("include/pmpm/core/b.hpp", '#include "pmpm/util/a.hpp"\n')
        put("src/core/b.cpp", '#include "pmpm/core/b.hpp"\n#include "pmpm/solvers/c.hpp"\n')
        put("include/pmpm/solvers/c.hpp", '#include "pmpm/core/b.hpp"\n')
        put("src/loose.cpp", '#include "pmpm/util/a.hpp"\n')
        bad, _, _ = check(t)
    want = ["src/core/b.cpp (core) includes pmpm/solvers/c.hpp (solvers), a layer above",
            "src/loose.cpp: not in a layer folder"]
    ok = len(bad) == 2 and all(any(b.startswith(w) for b in bad) for w in want)
    if not ok:
        print("layers: the self-check on a synthetic tree failed:", bad)
    return ok


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    root = args[0] if args else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    if not self_check():
        return 1
    bad, graph, files = check(root)
    if "--graph" in sys.argv:
        for name in LAYERS:
            below = sorted(graph.get(name, set()) - {name}, key=RANK.get)
            print(f"{name:10s} -> {', '.join(below) if below else '-'}")
    for b in bad:
        print(b)
    print(f"layers: {files} files in {len(LAYERS)} layers, {len(bad)} violation(s)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
