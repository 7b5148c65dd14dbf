#!/usr/bin/python3
r"""Plot a pmpm landfill-cover run in the style of the seed paper's Figures 7-9.

Seed paper section 4 (landfill cover over a soft zone): Figure 7 deformation contour plot,
Figure 8 axial strain in the geomembrane, Figure 9 axial stress in the geomembrane.

Usage (Debian python, not pyenv):
    /usr/bin/python3 scripts/plot_landfill.py OUTDIR
    /usr/bin/python3 scripts/plot_landfill.py OUTDIR --compare OTHER_OUTDIR \
        --labels "load II" "load I"

Reads
    OUTDIR/membrane_profile.csv  header, then s0,x0,y0,x,y,ux,uy,strain_chain,strain_particle,
                                 stress_axial (mid-layer geomembrane particles; m, Pa, fractions)
    OUTDIR/particles.h5          /particles/position (N x 2), /particles/position0 (N x 2),
                                 /particles/stress (N x 4), /particles/material (N),
                                 /particles/volume (N)
    OUTDIR/summary.json          optional; "results" with settlement_centre, peak_axial_strain, ...
Writes PNGs in OUTDIR: deformed_shape.png, membrane_deflection.png, membrane_strain.png,
membrane_stress.png. With --compare, the three membrane plots overlay both runs (only
membrane_profile.csv is needed in OTHER_OUTDIR); deformed_shape.png is always OUTDIR's run.
Exits non-zero with a message naming the file if an input is missing or malformed.
"""

import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

PROFILE_COLUMNS = ["s0", "x0", "y0", "x", "y", "ux", "uy", "strain_chain", "strain_particle",
                   "stress_axial"]
M_TO_MM = 1e3
RUN_COLOURS = ["tab:blue", "tab:red", "tab:green", "tab:purple"]


class InputError(Exception):
    pass


def require_file(path):
    if not os.path.isfile(path):
        raise InputError(f"missing input file: {path}")
    return path


def read_profile(outdir):
    """Membrane mid-layer profile as a dict of 1-D arrays, sorted by initial arc length s0."""
    path = require_file(os.path.join(outdir, "membrane_profile.csv"))
    with open(path) as f:
        header = f.readline().strip()
    names = [c.strip() for c in header.split(",")]
    missing = [c for c in PROFILE_COLUMNS if c not in names]
    if missing:
        raise InputError(f"{path}: header lacks column(s) {', '.join(missing)}; got: {header}")
    try:
        data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    except ValueError as e:
        raise InputError(f"{path}: cannot parse numbers: {e}") from e
    if data.shape[0] < 2 or data.shape[1] != len(names):
        raise InputError(f"{path}: expected >= 2 rows of {len(names)} columns, got {data.shape}")
    prof = {c: data[:, names.index(c)] for c in PROFILE_COLUMNS}
    order = np.argsort(prof["s0"], kind="stable")
    return {c: v[order] for c, v in prof.items()}


def read_particles(outdir):
    path = require_file(os.path.join(outdir, "particles.h5"))
    import h5py

    out = {}
    try:
        with h5py.File(path, "r") as f:
            for name in ["position", "position0", "material", "volume"]:
                key = "/particles/" + name
                if key not in f:
                    raise InputError(f"{path}: missing dataset {key}")
                out[name] = np.asarray(f[key][...])
    except OSError as e:
        raise InputError(f"{path}: cannot read HDF5: {e}") from e
    n = out["position"].shape[0]
    if out["position"].ndim != 2 or out["position"].shape[1] < 2:
        raise InputError(f"{path}: /particles/position must be N x 2, got {out['position'].shape}")
    if out["position0"].shape != out["position"].shape:
        raise InputError(f"{path}: /particles/position0 shape {out['position0'].shape} differs "
                         f"from /particles/position {out['position'].shape}")
    for name in ["material", "volume"]:
        if out[name].reshape(-1).shape[0] != n:
            raise InputError(f"{path}: /particles/{name} has {out[name].size} entries, need {n}")
        out[name] = out[name].reshape(-1)
    return out


def read_summary(outdir):
    path = os.path.join(outdir, "summary.json")
    if not os.path.isfile(path):
        return None
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        print(f"warning: ignoring unreadable {path}: {e}", file=sys.stderr)
        return None


def summary_text(summary):
    """One-line digest of summary.json 'results' (lengths in mm, strains in %)."""
    if not summary or not isinstance(summary.get("results"), dict):
        return ""
    r = summary["results"]
    parts = []
    if isinstance(r.get("settlement_centre"), (int, float)):
        parts.append(f"settlement at centre {r['settlement_centre'] * M_TO_MM:.3f} mm")
    if isinstance(r.get("peak_axial_strain"), (int, float)):
        parts.append(f"peak axial strain {100 * r['peak_axial_strain']:.2f} %")
    return ", ".join(parts)


def mark_void(ax, void_mm):
    for xv in void_mm:
        ax.axvline(xv, color="0.6", lw=0.8, ls="-", zorder=0)


def x_of(prof, xaxis):
    return (prof["x0"] if xaxis == "initial" else prof["x"]) * M_TO_MM


def x_label(xaxis):
    return "X (mm, initial position)" if xaxis == "initial" else "X (mm, current position)"


def plot_deformed(outdir, parts, prof, void_mm, title_extra):
    pos = parts["position"][:, :2] * M_TO_MM
    uy = (parts["position"][:, 1] - parts["position0"][:, 1]) * M_TO_MM
    mag = np.abs(uy)
    xmin, xmax = pos[:, 0].min(), pos[:, 0].max()
    ymin, ymax = pos[:, 1].min(), pos[:, 1].max()
    width = max(xmax - xmin, 1e-12)
    height = max(ymax - ymin, 1e-12)
    fig_w = 7.0
    fig_h = min(12.0, max(3.0, fig_w * 0.85 * height / width + 1.2))
    fig, ax = plt.subplots(figsize=(fig_w, fig_h))
    ax.set_aspect("equal")
    pad = 0.02 * max(width, height)
    ax.set_xlim(xmin - pad, xmax + pad)
    ax.set_ylim(ymin - pad, ymax + pad)
    sc = ax.scatter(pos[:, 0], pos[:, 1], c=mag, s=1.0, marker="s", linewidths=0,
                    cmap="viridis", vmin=0.0, vmax=max(mag.max(), 1e-12))
    ax.plot(prof["x"] * M_TO_MM, prof["y"] * M_TO_MM, color="w", lw=0.8, alpha=0.9)
    mark_void(ax, void_mm)
    from mpl_toolkits.axes_grid1 import make_axes_locatable

    cax = make_axes_locatable(ax).append_axes("right", size="4%", pad=0.1)
    cb = fig.colorbar(sc, cax=cax)
    cb.set_label("|vertical displacement| (mm)")
    ax.set_xlabel("X (mm)")
    ax.set_ylabel("Y (mm)")
    title = "Deformed configuration (cf. paper Fig. 7); white line: geomembrane mid-layer"
    if title_extra:
        title += "\n" + title_extra
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    # Now that the layout is final: marker area (points^2) so that a square of side
    # 1.15 sqrt(V_p) covers the particle's own area with a little overlap (no white gaps).
    fig.canvas.draw()
    bbox = ax.get_window_extent()
    x0, x1 = ax.get_xlim()
    pts_per_mm = bbox.width / (x1 - x0) * 72.0 / fig.dpi
    side_mm = 1.15 * np.sqrt(np.clip(parts["volume"], 0, None)) * M_TO_MM
    sc.set_sizes((side_mm * pts_per_mm) ** 2)
    out = os.path.join(outdir, "deformed_shape.png")
    fig.savefig(out, dpi=150)
    plt.close(fig)
    return out


def profile_figure(runs, void_mm, xaxis, ylabel, title, curves, outpath):
    """curves: list of (column, scale, curve label, linestyle, marker)."""
    fig, ax = plt.subplots(figsize=(7.5, 4.5))
    mark_void(ax, void_mm)
    multi = len(runs) > 1
    for k, (label, prof) in enumerate(runs):
        colour = RUN_COLOURS[k % len(RUN_COLOURS)]
        for col, scale, clabel, ls, mk in curves:
            parts = [p for p in (label if multi else "", clabel) if p]
            ax.plot(x_of(prof, xaxis), prof[col] * scale, color=colour, ls=ls, marker=mk,
                    ms=2.5, lw=1.2, label=", ".join(parts) if parts else None)
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel(x_label(xaxis))
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    ax.grid(True, lw=0.3, alpha=0.5)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(outpath, dpi=150)
    plt.close(fig)
    return outpath


def main(argv=None):
    ap = argparse.ArgumentParser(
        description="Plot a pmpm landfill run (paper Figures 7-9) into PNGs in OUTDIR.")
    ap.add_argument("outdir", help="run output directory (membrane_profile.csv, particles.h5)")
    ap.add_argument("--compare", metavar="OTHER_OUTDIR",
                    help="overlay this run's membrane profile on the profile plots")
    ap.add_argument("--labels", nargs=2, metavar=("LABEL", "OTHER_LABEL"),
                    help='legend labels for OUTDIR and OTHER_OUTDIR, e.g. "load II" "load I"')
    ap.add_argument("--void", nargs=2, type=float, default=[12.0, 18.0], metavar=("X1", "X2"),
                    help="void (soft zone) edges in mm, drawn as light vertical lines "
                         "(default 12 18)")
    ap.add_argument("--xaxis", choices=["initial", "current"], default="initial",
                    help="abscissa of the membrane plots: initial x0 (default) or current x")
    args = ap.parse_args(argv)
    if args.labels and not args.compare:
        ap.error("--labels needs --compare")

    try:
        if not os.path.isdir(args.outdir):
            raise InputError(f"not a directory: {args.outdir}")
        prof = read_profile(args.outdir)
        parts = read_particles(args.outdir)
        summary = read_summary(args.outdir)
        labels = args.labels or [os.path.basename(os.path.normpath(args.outdir)),
                                 os.path.basename(os.path.normpath(args.compare or "other"))]
        runs = [(labels[0], prof)]
        if args.compare:
            if not os.path.isdir(args.compare):
                raise InputError(f"not a directory: {args.compare}")
            runs.append((labels[1], read_profile(args.compare)))
    except InputError as e:
        print(f"plot_landfill.py: error: {e}", file=sys.stderr)
        return 2

    digest = summary_text(summary)
    if digest:
        print(f"{args.outdir}: {digest}")
    written = [plot_deformed(args.outdir, parts, prof, args.void, digest)]
    suffix = " (" + " vs ".join(l for l, _ in runs) + ")" if len(runs) > 1 else ""
    written.append(profile_figure(
        runs, args.void, args.xaxis, "vertical displacement $u_y$ (mm)",
        "Geomembrane vertical displacement" + suffix, [("uy", M_TO_MM, "", "-", ".")],
        os.path.join(args.outdir, "membrane_deflection.png")))
    written.append(profile_figure(
        runs, args.void, args.xaxis, "axial strain (%)",
        "Axial strain in geomembrane (cf. paper Fig. 8)" + suffix,
        [("strain_chain", 100.0, "chain strain", "-", "."),
         ("strain_particle", 100.0, "particle strain", "--", None)],
        os.path.join(args.outdir, "membrane_strain.png")))
    written.append(profile_figure(
        runs, args.void, args.xaxis, "axial stress (MPa)",
        "Axial stress in geomembrane (cf. paper Fig. 9)" + suffix,
        [("stress_axial", 1e-6, "", "-", ".")],
        os.path.join(args.outdir, "membrane_stress.png")))
    for w in written:
        print(f"wrote {w}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
