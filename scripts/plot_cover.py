#!/usr/bin/python3
r"""Plot a staged `cover` run of pmpm: the stage history and the deformed model.

Usage (Debian python, not pyenv):
    /usr/bin/python3 scripts/plot_cover.py OUTDIR

Reads from OUTDIR (as written by `-scene cover`):
    stages.csv                 one row per stage (stage 0 geostatic, then shrink / void stages)
    summary.json               optional: allowable strain, the void's width B (results.void)
    series/stage_NNN.h5        one particle frame per stage (the last one is drawn)
    chain_<name>.csv           optional: the membranes' final profiles (x, y)
Writes into OUTDIR:
    stages.png                 left: peak membrane strain (%) against differential settlement
                               (m), one point per stage labelled by its number, with the
                               allowable strain as a dashed line when summary.json gives it;
                               right: peak membrane tension (kN/m) against stage and, when there
                               is a void stage, the mean pressure on the sheet over the void
                               (kPa, right-hand axis)
    cover_deformed.png         the last stage's deformed particles, each drawn as its deformed
                               domain x + F (+-lx, +-ly) and filled by its equivalent plastic
                               strain eps_p (particles that never yielded: a grey per material),
                               with the membranes' polylines on top in black; true scale
    cover_deformed_zoom.png    only with a void (summary results.void): the same picture in a
                               window 4 B wide (and at most 4 B tall) around the void's centre
Prints the files written. Exits non-zero with a message if OUTDIR has no stages.csv or a frame
is unreadable.
"""

import csv
import glob
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib import colors as mcolors  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
from mpl_toolkits.axes_grid1 import make_axes_locatable  # noqa: E402

import h5py  # noqa: E402

# Greys for particles that never yielded (eps_p below the colour scale's floor), by material
# index (0 = waste, then the cover layers); cycled for more layers.
ELASTIC_GREYS = ["0.62", "0.80", "0.70", "0.88", "0.75"]
# Lowest eps_p on the logarithmic colour scale, relative to the largest one (and never below
# EPS_FLOOR_ABS): three decades show where the cover yields without drowning it in noise.
EPS_DECADES = 3.0
EPS_FLOOR_ABS = 1e-5
# Polygons are drawn without antialiasing (antialiased neighbours leave faint seams of background
# between them) and with an edge of their own colour this wide (points), which closes sub-pixel
# gaps between neighbouring domains; the edge is not visible as a line (same colour).
SEAM_WIDTH = 0.3


def fail(msg):
    sys.exit(f"plot_cover.py: {msg}")


# ------------------------------------------------------------------------------------------------
# input
def read_stages(path):
    """stages.csv as a dict of column name -> numpy array (kind stays a list of strings)."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        fail(f"{path} has no stage rows")
    out = {}
    for key in rows[0]:
        vals = [r[key] for r in rows]
        if key in ("kind", "verdict"):
            out[key] = vals
        else:
            try:
                out[key] = np.array([float(v) for v in vals])
            except ValueError:
                fail(f"{path}: column {key} is not numeric")
    for key in ("stage", "differential_settlement", "peak_strain", "peak_tension"):
        if key not in out:
            fail(f"{path} lacks the column {key}")
    return out


def read_summary(outdir):
    """summary.json's "results" dict, or {} when the file is missing."""
    path = os.path.join(outdir, "summary.json")
    if not os.path.isfile(path):
        return {}
    try:
        with open(path) as f:
            return json.load(f).get("results", {})
    except (OSError, ValueError) as e:
        print(f"plot_cover.py: warning: ignoring unreadable {path}: {e}", file=sys.stderr)
        return {}


def read_frame(path):
    """The particle fields needed for the deformed picture, from one series frame."""
    try:
        with h5py.File(path, "r") as f:
            g = f["particles"]
            x = g["position"][:].reshape(-1, 2)
            F = g["F"][:].reshape(-1, 4)
            n = x.shape[0]
            if "halfsize" in g:
                hs = g["halfsize"][:].reshape(-1, 2)
            else:  # older output: square particles of the initial volume
                h = 0.5 * np.sqrt(g["volume0"][:].reshape(-1))
                hs = np.column_stack([h, h])
            eps = g["eps_p"][:].reshape(-1) if "eps_p" in g else np.zeros(n)
            mat = g["material"][:].reshape(-1).astype(int) if "material" in g else np.zeros(
                n, int)
            ids = g["id"][:].reshape(-1).astype(np.int64) if "id" in g else None
            x0 = g["position0"][:].reshape(-1, 2) if "position0" in g else x
    except (OSError, KeyError) as e:
        fail(f"cannot read {path}: {e}")
    return dict(x=x, F=F, hs=hs, eps=eps, mat=mat, ids=ids, x0=x0)


def read_chains(outdir):
    """The membranes' final polylines: list of (name, x, y), ordered along each chain."""
    chains = []
    for path in sorted(glob.glob(os.path.join(outdir, "chain_*.csv"))):
        try:
            d = np.genfromtxt(path, delimiter=",", names=True)
            order = np.argsort(d["s0"])
            name = os.path.basename(path)[len("chain_"):-len(".csv")]
            chains.append((name, d["x"][order], d["y"][order]))
        except (ValueError, KeyError, IndexError) as e:
            print(f"plot_cover.py: warning: skipping {path}: {e}", file=sys.stderr)
    return chains


# ------------------------------------------------------------------------------------------------
# stage history
def plot_stages(st, res, path):
    stage = st["stage"].astype(int)
    diff = st["differential_settlement"]
    strain = 100.0 * st["peak_strain"]
    tension = 1e-3 * st["peak_tension"]
    conv = st.get("converged", np.ones_like(diff)).astype(bool)

    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 4.6))
    a1.plot(diff, strain, "-", color="tab:blue", lw=1.2, zorder=1)
    a1.scatter(diff[conv], strain[conv], color="tab:blue", zorder=2, label="converged")
    if not conv.all():
        a1.scatter(diff[~conv], strain[~conv], facecolor="white", edgecolor="tab:red",
                   zorder=2, label="not converged")
    for s, x, y in zip(stage, diff, strain):
        a1.annotate(str(s), (x, y), textcoords="offset points", xytext=(5, 5), fontsize=9)
    allow = res.get("membrane", {}).get("allowable_strain")
    if allow:
        a1.axhline(100.0 * allow, ls="--", color="tab:red",
                   label=f"allowable {100.0 * allow:g} %")
    a1.set_xlabel("differential settlement of the membrane (m)")
    a1.set_ylabel("peak membrane strain (%)")
    a1.set_title("membrane strain per stage (labels: stage)")
    a1.set_ylim(0, 1.15 * max(np.max(strain), 100.0 * (allow or 0.0), 1e-3))
    a1.grid(alpha=0.3)
    a1.legend(loc="best", fontsize=9)

    a2.plot(stage, tension, "o-", color="tab:blue", label="peak tension")
    a2.set_xlabel("stage")
    a2.set_ylabel("peak membrane tension (kN/m)", color="tab:blue")
    a2.set_xticks(stage)
    a2.set_ylim(0, 1.15 * max(np.max(tension), 1e-3))
    a2.grid(alpha=0.3)
    handles = a2.get_lines()[:]
    is_void = np.array([k == "void" for k in st["kind"]])
    if is_void.any() and "void_pressure" in st:
        a3 = a2.twinx()
        h, = a3.plot(stage[is_void], 1e-3 * st["void_pressure"][is_void], "s--",
                     color="tab:orange", label="pressure on the sheet over the void")
        a3.set_ylabel("pressure over the void (kPa)", color="tab:orange")
        a3.set_ylim(0, 1.15 * max(1e-3 * np.max(st["void_pressure"][is_void]), 1e-3))
        handles.append(h)
    a2.legend(handles=handles, loc="upper left", fontsize=9)
    kinds = ", ".join(f"{s}: {k}" for s, k in zip(stage, st["kind"]))
    a2.set_title(f"stages ({kinds})", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


# ------------------------------------------------------------------------------------------------
# deformed model
def particle_polygons(fr):
    """(n, 4, 2) corners of each particle's deformed domain x + F (+-lx, +-ly), vectorised."""
    corners = np.array([[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]])  # (4, 2)
    off = corners[None, :, :] * fr["hs"][:, None, :]                            # (n, 4, 2)
    F = fr["F"].reshape(-1, 2, 2)                                               # row-major
    return fr["x"][:, None, :] + np.einsum("nij,nkj->nki", F, off)


def eps_norm(eps):
    """A log colour norm over the yielded range of eps_p, or None if nothing yielded."""
    emax = float(np.max(eps)) if eps.size else 0.0
    if not emax > 0:
        return None
    vmin = max(emax * 10.0 ** -EPS_DECADES, EPS_FLOOR_ABS)
    if vmin >= emax:
        vmin = 0.5 * emax
    return mcolors.LogNorm(vmin=vmin, vmax=emax)


def face_colours(fr, norm, cmap):
    """RGBA per particle: cmap(eps_p) where it yielded, else a grey for its material."""
    n = fr["x"].shape[0]
    rgba = np.empty((n, 4))
    greys = np.array([mcolors.to_rgba(c) for c in ELASTIC_GREYS])
    rgba[:] = greys[fr["mat"] % len(greys)]
    if norm is not None:
        yielded = fr["eps"] >= norm.vmin
        rgba[yielded] = cmap(norm(fr["eps"][yielded]))
    return rgba


def void_centre(fr, fr0, res, chains):
    """(xc, yc, B) of the void: the mean initial position of the particles removed since stage 0
    (ids present in the first frame, absent in the last); else the membrane's peak strain x and
    the membrane's height there. None when there is no void."""
    void = res.get("void")
    if not void:
        return None
    B = float(void.get("B", 0.0))
    if not B > 0:
        return None
    if fr0 is not None and fr["ids"] is not None and fr0["ids"] is not None:
        gone = ~np.isin(fr0["ids"], fr["ids"])
        if gone.any():
            xc, yc = fr0["x0"][gone].mean(axis=0)
            return float(xc), float(yc), B
    xc = res.get("membrane", {}).get("peak_strain_x")
    if xc is None:
        return None
    yc = float(np.median(fr["x"][:, 1]))
    if chains:
        _, cx, cy = chains[0]
        yc = float(np.interp(xc, cx, cy))
    return float(xc), yc, B


def plot_deformed(fr, chains, title, path, window=None):
    """Draw the particles' deformed domains filled by eps_p; window = (x0, x1, y0, y1)."""
    polys = particle_polygons(fr)
    keep = np.ones(len(polys), bool)
    if window is not None:  # cull what is outside the window (speed, file size)
        x0, x1, y0, y1 = window
        lo, hi = polys.min(axis=1), polys.max(axis=1)
        keep = (hi[:, 0] >= x0) & (lo[:, 0] <= x1) & (hi[:, 1] >= y0) & (lo[:, 1] <= y1)
    cmap = plt.get_cmap("plasma")
    norm = eps_norm(fr["eps"][keep] if window is not None and keep.any() else fr["eps"])
    fc = face_colours(fr, norm, cmap)

    ext = polys[keep].reshape(-1, 2)
    lo, hi = ext.min(axis=0), ext.max(axis=0)
    if window is None:
        window = (lo[0], hi[0], lo[1], hi[1])
    wx, wy = window[1] - window[0], window[3] - window[2]
    width = 12.0
    height = min(max(width * wy / wx * 0.95 + 1.6, 3.2), 11.0)
    fig, ax = plt.subplots(figsize=(width, height))
    pc = PolyCollection(polys[keep], facecolors=fc[keep], edgecolors=fc[keep],
                        linewidths=SEAM_WIDTH, antialiaseds=False)
    ax.add_collection(pc)
    for k, (name, cx, cy) in enumerate(chains):
        ax.plot(cx, cy, "-", color="black", lw=1.4, label=f"membrane {name}" if k < 4 else None,
                zorder=3)
    ax.set_xlim(window[0], window[1])
    ax.set_ylim(window[2], window[3])
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(title, fontsize=10)
    if chains:
        ax.legend(loc="lower right", fontsize=8, framealpha=0.85)
    if norm is not None:
        sm = plt.cm.ScalarMappable(norm=norm, cmap=cmap)
        # a colour bar as tall as the (equal-aspect) axes
        cax = make_axes_locatable(ax).append_axes("right", size=0.18, pad=0.12)
        cb = fig.colorbar(sm, cax=cax, extend="min")
        cb.set_label("equivalent plastic strain eps_p (grey: elastic)")
    fig.tight_layout()
    fig.savefig(path, dpi=150, bbox_inches="tight")
    plt.close(fig)


# ------------------------------------------------------------------------------------------------
def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(argv) == 2 else 2
    outdir = argv[1]
    stages_csv = os.path.join(outdir, "stages.csv")
    if not os.path.isfile(stages_csv):
        fail(f"{stages_csv} not found: not the output directory of a `-scene cover` run")
    st = read_stages(stages_csv)
    res = read_summary(outdir)
    written = []

    path = os.path.join(outdir, "stages.png")
    plot_stages(st, res, path)
    written.append(path)

    frames = sorted(glob.glob(os.path.join(outdir, "series", "stage_*.h5")))
    if not frames:
        print(f"plot_cover.py: warning: no {outdir}/series/stage_*.h5: no deformed picture",
              file=sys.stderr)
    elif os.path.isfile(os.path.join(outdir, "sheets.h5")):  # -dim 3: the sheet's own plots
        print(f"plot_cover.py: a 3D cover: its sheet's plan map and sections are "
              f"scripts/plot_sheet.py's (the particles' deformed picture here is 2D only)", file=sys.stderr)
    else:
        fr = read_frame(frames[-1])
        chains = read_chains(outdir)
        last = int(os.path.basename(frames[-1])[len("stage_"):-len(".h5")])
        kinds = dict(zip(st["stage"].astype(int), st["kind"]))
        kind = kinds.get(last, "?")
        title = (f"{os.path.basename(os.path.normpath(outdir))}: stage {last} ({kind}), "
                 f"{len(fr['x'])} particles, deformed domains (true scale), "
                 f"max eps_p {fr['eps'].max():.3g}")
        path = os.path.join(outdir, "cover_deformed.png")
        plot_deformed(fr, chains, title, path)
        written.append(path)

        fr0 = read_frame(frames[0]) if len(frames) > 1 else None
        vc = void_centre(fr, fr0, res, chains)
        if vc is not None:
            xc, yc, B = vc
            lo = np.minimum(fr["x"].min(axis=0), fr["x0"].min(axis=0))
            hi = np.maximum(fr["x"].max(axis=0), fr["x0"].max(axis=0))
            pad = 0.05 * B
            window = (xc - 2 * B, xc + 2 * B, max(yc - 2 * B, lo[1] - pad),
                      min(yc + 2 * B, hi[1] + pad))
            path = os.path.join(outdir, "cover_deformed_zoom.png")
            plot_deformed(fr, chains, title + f"\nzoom: 4 B around the void "
                          f"(B = {B:g} m, centre x = {xc:.3g} m)", path, window)
            written.append(path)

    for p in written:
        print(p)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
