#!/usr/bin/env python3
"""Check that the source folders form layers: a file may include headers of its own folder and of
the folders below it, never above.

The layers, bottom to top (docs/developer-guide.md, "Layers"):

  util       config, options, logging, JSON and HDF5 helpers: no physics
  materials  constitutive laws of the continuum and of the membranes
  core       grid, particles, shapes, transfers: the kernels of one MPM step
  contact    what couples bodies on the grid: stacked-body contact, chains, the colour interface
  model      Simulation (settings, state, scratch), geometry, loads, stages' data, design answers
  io         HDF5 + XDMF, checkpoints, summaries, the partition by particle counts
  step       the explicit step as named phases and its hooks; the stress update
  solvers    equilibrium solvers (dynamic relaxation, Newton) and the stage loop
  scenes     scenes (problem set-ups) and their closed forms
  app        main

A file's folder is its directory under src/ or include/pmpm/ (files directly in src/ or
include/pmpm/ are refused: every file sits in a layer). Run from anywhere:
  python3 scripts/layers.py          # prints violations, exit 1 if any
  python3 scripts/layers.py --graph  # the folder graph (which layer includes which)
"""
import os
import re
import sys

LAYERS = ["util", "materials", "core", "contact", "model", "io", "step", "solvers", "scenes",
          "app"]
RANK = {name: i for i, name in enumerate(LAYERS)}
INCLUDE = re.compile(r'^\s*#\s*include\s+"pmpm/([^"]+)"', re.M)


def layer_of(rel):
    """rel: a path relative to src/ or include/pmpm/; its first folder."""
    parts = rel.split("/")
    return parts[0] if len(parts) > 1 else None


def main():
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    bad, graph, files = [], {}, 0
    for base in ("src", os.path.join("include", "pmpm")):
        top = os.path.join(root, base)
        for d, _, names in os.walk(top):
            for n in names:
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
    if "--graph" in sys.argv:
        for name in LAYERS:
            below = sorted(graph.get(name, set()) - {name}, key=RANK.get)
            print(f"{name:10s} -> {', '.join(below) if below else '-'}")
    for b in bad:
        print(b)
    print(f"layers: {files} files, {len(bad)} violation(s)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
