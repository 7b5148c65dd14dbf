#!/usr/bin/python3
r"""Plot the geomembrane chains of pmpm runs: strain, tension, interface slip, contact pressure
and shape along each chain.

Usage (Debian python, not pyenv):
    /usr/bin/python3 scripts/plot_chain.py OUTDIR [OUTDIR2 ...] [--scale F]

Reads every OUTDIR/chain_<name>.csv: a header line, then comma-separated rows with the columns
    s0,x0,y0,x,y,ux,uy,strain,tension,slack,slip_top,slip_bottom,pressure_top,pressure_bottom
(s0 initial arc length, positions and displacements in m, strain dimensionless, tension N/m,
slack 0/1, slips m, pressures Pa). Extra columns are ignored; rows are sorted by s0.
Writes, for each chain, into its OUTDIR:
    chain_<name>_strain.png     axial strain (%) against s0 (in mm for chains under 0.1 m)
    chain_<name>_tension.png    axial force per width (kN/m) against s0
    chain_<name>_slip.png       slip on the top and bottom faces against s0
    chain_<name>_pressure.png   contact pressure on the top and bottom faces against s0
    chain_<name>_shape.png      initial and deformed y against x
Slack stretches (the sheet carries no force in compression) are shaded grey on the plots against
s0 (on the overlays: a strip per run along the bottom, in the run's colour) and marked on the
deformed shape. The shape's axes are not to scale (y autoscales); the
deformed shape is exaggerated when the largest displacement is under 2 % of the chain's initial
height range, e.g. on a slope (the factor is in the legend and title); --scale F forces the
factor (--scale 1: true scale).
With several OUTDIRs, each chain found in the first and in at least one other is also overlaid
across them, written into the first OUTDIR as chain_<name>_compare_{strain,tension,slip,pressure,
shape}.png and labelled by the directories' basenames.
Exits non-zero with a message naming the file if an input is missing or malformed; a
chain_*.csv whose header lacks the columns above is skipped with a warning.
"""

import argparse
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

COLUMNS = ["s0", "x0", "y0", "x", "y", "ux", "uy", "strain", "tension", "slack", "slip_top",
           "slip_bottom", "pressure_top", "pressure_bottom"]
RUN_COLOURS = ["tab:blue", "tab:red", "tab:green", "tab:purple", "tab:orange", "tab:brown"]
SLACK_COLOUR = "0.6"
# The y axis autoscales, so a flat chain's deflection is always visible at true scale; a chain
# with a large initial height range (a slope) hides it. Exaggerate when max |u| is under 2 % of
# the initial height range, to about 10 % of it (rounded to 1, 2 or 5 x 10^k).
AUTO_EXAGGERATE_BELOW = 0.02
AUTO_EXAGGERATE_TO = 0.10


class InputError(Exception):
    pass


class NotAChain(Exception):
    pass


def read_chain(path):
    """One chain CSV as a dict of 1-D arrays, sorted by s0."""
    with open(path) as f:
        header = f.readline().strip()
    names = [c.strip() for c in header.split(",")]
    missing = [c for c in COLUMNS if c not in names]
    if missing:
        raise NotAChain(f"{path}: header lacks column(s) {', '.join(missing)}")
    try:
        data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    except ValueError as e:
        raise InputError(f"{path}: cannot parse numbers: {e}") from e
    if data.shape[0] < 2 or data.shape[1] != len(names):
        raise InputError(f"{path}: expected >= 2 rows of {len(names)} columns, got {data.shape}")
    chain = {c: data[:, names.index(c)] for c in COLUMNS}
    order = np.argsort(chain["s0"], kind="stable")
    chain = {c: v[order] for c, v in chain.items()}
    chain["slack"] = chain["slack"] > 0.5
    return chain


def find_chains(outdir):
    """{name: path} of the chain_<name>.csv files in outdir (not our own outputs)."""
    if not os.path.isdir(outdir):
        raise InputError(f"not a directory: {outdir}")
    found = {}
    for path in sorted(glob.glob(os.path.join(outdir, "chain_*.csv"))):
        found[os.path.basename(path)[len("chain_"):-len(".csv")]] = path
    return found


def run_labels(dirs):
    """Basename of each directory; parent/basename where basenames repeat."""
    norm = [os.path.normpath(os.path.abspath(d)) for d in dirs]
    base = [os.path.basename(d) for d in norm]
    if len(set(base)) == len(base):
        return base
    return [os.path.join(os.path.basename(os.path.dirname(d)), b) for d, b in zip(norm, base)]


def slack_runs(s0, slack):
    """Contiguous slack stretches as (start, end) in s0, each point owning half of the segments
    beside it (a single slack point shows as a band one segment wide)."""
    mid = 0.5 * (s0[1:] + s0[:-1])
    lo = np.concatenate([[s0[0]], mid])
    hi = np.concatenate([mid, [s0[-1]]])
    runs, start = [], None
    for i, sl in enumerate(slack):
        if sl and start is None:
            start = lo[i]
        if not sl and start is not None:
            runs.append((start, hi[i - 1]))
            start = None
    if start is not None:
        runs.append((start, hi[-1]))
    return runs


def length_unit(values):
    """('mm', 1e3) for lengths under 0.1 m, else ('m', 1)."""
    vmax = max((float(np.max(np.abs(v))) for v in values if v.size), default=0.0)
    return ("mm", 1e3) if vmax < 0.1 else ("m", 1.0)


def nice_factor(x):
    """Smallest 1, 2 or 5 x 10^k that is >= x."""
    k = np.floor(np.log10(x))
    for m in (1.0, 2.0, 5.0, 10.0):
        if m * 10.0**k >= x * (1 - 1e-12):
            return m * 10.0**k
    return 10.0 ** (k + 1)


def exaggeration(runs, forced):
    if forced is not None:
        return forced
    extent = max(float(np.ptp(c["y0"])) for _, c, _ in runs)
    umax = max(float(np.max(np.hypot(c["ux"], c["uy"]))) for _, c, _ in runs)
    if extent <= 0 or umax <= 0 or umax >= AUTO_EXAGGERATE_BELOW * extent:
        return 1.0
    return nice_factor(AUTO_EXAGGERATE_TO * extent / umax)


def shade_slack(ax, runs, k):
    """Slack stretches: grey bands over the full height for one run; with several runs, a strip
    per run along the bottom of the axes in the run's colour (so the runs do not overlap)."""
    for i, (label, c, colour) in enumerate(runs):
        name = "slack" if len(runs) == 1 else f"{label}: slack"
        for a, b in slack_runs(k * c["s0"], c["slack"]):
            if len(runs) == 1:
                ax.axvspan(a, b, color=SLACK_COLOUR, alpha=0.25, lw=0, label=name)
            else:
                ax.axvspan(a, b, ymin=0.04 * i, ymax=0.04 * (i + 1), color=colour, alpha=0.45,
                           lw=0, label=name)
            name = None


def finish(fig, ax, path, title):
    ax.set_title(title, fontsize=10)
    ax.grid(True, alpha=0.3)
    handles, _ = ax.get_legend_handles_labels()
    if handles:
        ax.legend(fontsize=8, loc="best")
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)
    print(f"plot_chain: wrote {path}")


def plot_along(runs, keys, ylabel, scale, path, title, face_styles=None):
    """Quantities keys (scaled by `scale`) against s0 (mm or m) for every run, slack shaded."""
    unit, k = length_unit([c["s0"] for _, c, _ in runs])
    fig, ax = plt.subplots(figsize=(7.5, 4.2))
    shade_slack(ax, runs, k)
    for label, c, colour in runs:
        for key in keys:
            line, face = (face_styles or {}).get(key, ("-", key))
            if len(keys) == 1:
                name = label if len(runs) > 1 else None
            else:
                name = f"{label}: {face}" if len(runs) > 1 else face
            ax.plot(k * c["s0"], scale * c[key], line, color=colour, lw=1.4, label=name)
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_xlabel(f"initial arc length s0 ({unit})")
    ax.set_ylabel(ylabel)
    finish(fig, ax, path, title)


FACES = {"slip_top": ("-", "top face"), "slip_bottom": ("--", "bottom face"),
         "pressure_top": ("-", "top face"), "pressure_bottom": ("--", "bottom face")}


def plot_shape(runs, forced_scale, path, title):
    f = exaggeration(runs, forced_scale)
    unit, k = length_unit([c[key] for _, c, _ in runs for key in ("x0", "y0")])
    fig, ax = plt.subplots(figsize=(7.5, 4.2))
    _, c0, _ = runs[0]
    ax.plot(k * c0["x0"], k * c0["y0"], ":", color="k", lw=1.2, label="initial")
    tag = "deformed" if f == 1.0 else f"deformed (displacement x {f:g})"
    for label, c, colour in runs:
        xd = c["x0"] + f * c["ux"]
        yd = c["y0"] + f * c["uy"]
        name = tag if len(runs) == 1 else f"{label}: {tag}"
        ax.plot(k * xd, k * yd, "-", color=colour, lw=1.6, label=name)
        if np.any(c["slack"]):
            ax.plot(k * xd[c["slack"]], k * yd[c["slack"]], "o", ms=3, mfc="none",
                    color=SLACK_COLOUR if len(runs) == 1 else colour,
                    label="slack points" if len(runs) == 1 else f"{label}: slack points")
    ax.set_xlabel(f"x ({unit})")
    ax.set_ylabel(f"y ({unit})")
    if f != 1.0:
        title += f"\ndeformed shape exaggerated x {f:g}"
    finish(fig, ax, path, title)


def plot_all(runs, prefix, title_tail, forced_scale):
    """The five plots of one chain for `runs` [(label, chain, colour)], files prefix_*.png."""
    slips = [c[k] for _, c, _ in runs for k in ("slip_top", "slip_bottom")]
    s_unit, s_k = length_unit(slips)
    plot_along(runs, ["strain"], "axial strain (%)", 100.0, prefix + "strain.png",
               f"axial strain, {title_tail}")
    plot_along(runs, ["tension"], "axial force per width T (kN/m)", 1e-3, prefix + "tension.png",
               f"axial tension, {title_tail}")
    plot_along(runs, ["slip_top", "slip_bottom"], f"interface slip ({s_unit})", s_k,
               prefix + "slip.png", f"slip on both faces, {title_tail}", FACES)
    plot_along(runs, ["pressure_top", "pressure_bottom"], "contact pressure (kPa)", 1e-3,
               prefix + "pressure.png", f"contact pressure on both faces, {title_tail}", FACES)
    plot_shape(runs, forced_scale, prefix + "shape.png", f"shape, {title_tail}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("outdirs", nargs="+", metavar="OUTPUT_DIR")
    ap.add_argument("--scale", type=float, default=None,
                    help="displacement exaggeration of the deformed shape (default: automatic)")
    args = ap.parse_args(argv)
    if args.scale is not None and not args.scale > 0:
        ap.error("--scale must be positive")
    labels = run_labels(args.outdirs)
    try:
        found = [find_chains(d) for d in args.outdirs]
        chains = [{} for _ in args.outdirs]  # per dir: name -> chain
        for i, paths in enumerate(found):
            for name, path in paths.items():
                try:
                    chains[i][name] = read_chain(path)
                except NotAChain as e:
                    print(f"plot_chain: warning: skipping {e}", file=sys.stderr)
        if not chains[0]:
            raise InputError(f"no chain_<name>.csv with columns {','.join(COLUMNS)} in "
                             f"{args.outdirs[0]}")
        for i, d in enumerate(args.outdirs):
            for name, c in sorted(chains[i].items()):
                plot_all([(labels[i], c, RUN_COLOURS[0])],
                         os.path.join(d, f"chain_{name}_"), f"chain '{name}' ({labels[i]})",
                         args.scale)
        if len(args.outdirs) > 1:
            for name in sorted(chains[0]):
                runs = [(labels[i], chains[i][name], RUN_COLOURS[i % len(RUN_COLOURS)])
                        for i in range(len(args.outdirs)) if name in chains[i]]
                if len(runs) < 2:
                    print(f"plot_chain: warning: chain '{name}' only in {args.outdirs[0]}, "
                          "no comparison", file=sys.stderr)
                    continue
                plot_all(runs, os.path.join(args.outdirs[0], f"chain_{name}_compare_"),
                         f"chain '{name}': " + " vs ".join(r[0] for r in runs), args.scale)
    except (InputError, OSError) as e:
        print(f"plot_chain: error: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
