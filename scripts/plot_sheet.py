#!/usr/bin/python3
r"""Plot the 3D geomembrane sheets of a pmpm run (-dim 3): the peak principal strain in plan and
the principal strains along sections through the sheet's centre.

Usage (Debian python, not pyenv):
    /usr/bin/python3 scripts/plot_sheet.py OUTDIR [--centre X,Z]

Reads OUTDIR/sheets.h5 (written by every run with a sheet; docs/outputs.md), group
/sheets/<name>/ with the datasets position0 (n x 3, the laid points, m), position, displacement,
triangles (nt x 3), strain_major / strain_minor (per point: the area-weighted mean of its
triangles' strain tensors, principal values) and triangle_strain_major (per triangle).
Writes, for each sheet, into OUTDIR:
    sheet_<name>_plan.png      the major principal strain (%) of each triangle over the laid
                               sheet in plan (x, z), the peak marked
    sheet_<name>_section.png   the major and minor principal strains (%) and the settlement (m)
                               of the points within half a lattice gap of the sections through
                               the centre along x and along z, against the distance from the
                               centre (--centre X,Z; else a 3D cover's round void, its centre
                               from OUTDIR/summary.json; else the free points' mean)
pmpm's vertical is y: a sheet spans x and z and settles along -y. Exits non-zero with a message
naming the file if the input is missing or malformed.
"""

import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.tri import Triangulation  # noqa: E402

try:
    import h5py  # noqa: E402
except ImportError:
    sys.exit("plot_sheet.py: needs python3-h5py (run it with /usr/bin/python3)")


def read(path):
    """Every sheet in sheets.h5: {name: {dataset: array}}."""
    try:
        with h5py.File(path, "r") as f:
            return {n: {k: np.array(g[k]) for k in g} for n, g in f["sheets"].items()}
    except (OSError, KeyError) as e:
        sys.exit(f"plot_sheet.py: cannot read {path}: {e}")


def plan(out, name, s):
    X0, tri, e1 = s["position0"], s["triangles"], 100 * s["triangle_strain_major"]
    t = Triangulation(X0[:, 0], X0[:, 2], tri)
    fig, ax = plt.subplots(figsize=(6.4, 5.4))
    pc = ax.tripcolor(t, facecolors=e1, cmap="viridis")
    k = int(np.argmax(e1))
    c = X0[tri[k]].mean(axis=0)
    ax.plot(c[0], c[2], "r+", ms=12, mew=2, label=f"peak {e1[k]:.3g} %")
    fig.colorbar(pc, ax=ax, label="major principal strain (%)")
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("z (m)")
    ax.set_title(f"sheet {name}: major principal strain per triangle\n(plan, laid positions)")
    ax.legend(loc="upper right")
    fig.tight_layout()
    fig.savefig(os.path.join(out, f"sheet_{name}_plan.png"), dpi=120)
    plt.close(fig)


def section(out, name, s, centre=None):
    X0, u = s["position0"], s["displacement"]
    free = s["pinned"] == 0
    c = X0[free].mean(axis=0) if free.any() else X0.mean(axis=0)
    if centre is not None:
        c[0], c[2] = centre
    # the lattice gap: the median edge length of the laid triangles
    tri = s["triangles"]
    gap = np.median(np.linalg.norm(X0[tri[:, 1]] - X0[tri[:, 0]], axis=1))
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7, 7), sharex=True)
    for axis, other, mk in ((0, 2, "o"), (2, 0, "s")):
        # the row of points nearest the section line (a lattice may be finer along one axis)
        near = np.min(np.abs(X0[:, other] - c[other]))
        sel = np.abs(X0[:, other] - c[other]) <= near + 0.25 * gap
        r = X0[sel, axis] - c[axis]
        o = np.argsort(r)
        lab = "x" if axis == 0 else "z"
        a1.plot(r[o], 100 * s["strain_major"][sel][o], mk + "-", ms=3, label=f"major, along {lab}")
        a1.plot(r[o], 100 * s["strain_minor"][sel][o], mk + "--", ms=3, label=f"minor, along {lab}")
        a2.plot(r[o], -u[sel, 1][o], mk + "-", ms=3, label=f"along {lab}")
    a1.set_ylabel("principal strain (%)")
    a1.legend(fontsize=8)
    a1.grid(alpha=0.3)
    a1.set_title(f"sheet {name}: sections through the centre (point means)")
    a2.set_ylabel("settlement (m)")
    a2.set_xlabel("distance from the centre (m)")
    a2.invert_yaxis()
    a2.legend(fontsize=8)
    a2.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out, f"sheet_{name}_section.png"), dpi=120)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("outdir")
    ap.add_argument("--centre", default=None,
                    help="X,Z of the sections' centre (m; default: the free points' mean)")
    a = ap.parse_args()
    centre = None
    try:  # a 3D cover's round void (summary.json, results.void.centre)
        import json
        with open(os.path.join(a.outdir, "summary.json")) as f:
            centre = json.load(f)["results"]["void"]["centre"]
    except (OSError, KeyError, TypeError, ValueError):
        pass
    if a.centre is not None:
        try:
            centre = [float(v) for v in a.centre.split(",")]
            assert len(centre) == 2
        except (ValueError, AssertionError):
            sys.exit(f"plot_sheet.py: --centre {a.centre}: give X,Z in metres (e.g. 0,0)")
    path = os.path.join(a.outdir, "sheets.h5")
    if not os.path.isfile(path):
        sys.exit(f"plot_sheet.py: {path} not found (a run with a 3D sheet writes it)")
    for name, s in read(path).items():
        need = ("position0", "displacement", "triangles", "strain_major", "strain_minor",
                "triangle_strain_major", "pinned")
        miss = [k for k in need if k not in s]
        if miss:
            sys.exit(f"plot_sheet.py: {path}: sheet {name} lacks {', '.join(miss)}")
        plan(a.outdir, name, s)
        section(a.outdir, name, s, centre)
        print(f"wrote {a.outdir}/sheet_{name}_plan.png and _section.png")


if __name__ == "__main__":
    main()
