#!/usr/bin/python3
r"""Plot a `trapdoor` run of pmpm: the ground reaction curve and the deformed soil.

Usage (Debian python, not pyenv):
    /usr/bin/python3 scripts/plot_trapdoor.py OUTDIR [OUTDIR ...]

Reads from each OUTDIR (as written by `-scene trapdoor`):
    trapdoor.csv      one row per stage: door displacement over B, pressure on the door over gamma H
    summary.json      H, B, Terzaghi's arching over gamma H for K = 1 and K = Ka (results)
    particles.h5      the final particles (deformed shape, eps_p)
Writes into the first OUTDIR:
    trapdoor.png            the curves (one per OUTDIR; a colour per H/B, dash-dot with F-bar),
                            with Terzaghi's K = 1 (dashed) and K = Ka (dotted) levels per H/B
    trapdoor_deformed.png   the first OUTDIR's final particles, each drawn as its deformed domain
                            filled by its equivalent plastic strain (plot_cover.py's drawing),
                            in a window 2.5 B wide around the door
Prints the files written.
"""
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plot_cover  # noqa: E402  (read_frame, plot_deformed)


def fail(msg):
    sys.exit(f"plot_trapdoor.py: {msg}")


def read_run(outdir):
    path = os.path.join(outdir, "trapdoor.csv")
    if not os.path.isfile(path):
        fail(f"{path} not found: not the output directory of a `-scene trapdoor` run")
    with open(path) as f:
        rows = list(csv.DictReader(f))
    d = [float(r["displacement_over_B"]) for r in rows]
    p = [float(r["pressure_over_gammaH"]) for r in rows]
    with open(os.path.join(outdir, "summary.json")) as f:
        res = json.load(f)["results"]
    # runs written before the scene reported it: F-bar from the directory's name
    res.setdefault("fbar", 1.0 if "fbar" in os.path.basename(os.path.normpath(outdir)) else 0.0)
    return d, p, res


def plot_curves(runs, path):
    """One colour per H/B: solid without F-bar, dash-dot with; Terzaghi K = 1 (dashed) and
    K = Ka (dotted) once per H/B."""
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    colours, drawn = {}, set()
    for d, p, res in runs:
        hb = res["height"] / res["door_width"]
        col = colours.setdefault(hb, f"C{len(colours)}")
        fb = res["fbar"] > 0
        ax.plot([100 * x for x in d], p, "s-." if fb else "o-", color=col, ms=3.0, lw=1.2,
                label=f"pmpm, H/B = {hb:g}" + (", F-bar" if fb else ""))
        if hb not in drawn:
            drawn.add(hb)
            ax.axhline(res["terzaghi_K1"], color=col, ls="--", lw=0.9,
                       label=f"Terzaghi K = 1 ({res['terzaghi_K1']:.3f})")
            ax.axhline(res["terzaghi_Ka"], color=col, ls=":", lw=1.1,
                       label=f"Terzaghi K = Ka ({res['terzaghi_Ka']:.3f})")
    ax.set_xlabel("door displacement / B (%)")
    ax.set_ylabel("pressure on the door / gamma H")
    ax.set_ylim(0, 1.05)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper right", ncol=2 if len(runs) > 1 else 1)
    ax.set_title(f"Active trapdoor, phi = {runs[0][2]['phi']:g} deg, c = 0", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=150)
    plt.close(fig)


def main(argv):
    if len(argv) < 2 or argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(argv) == 2 else 2
    runs = [read_run(o) for o in argv[1:]]
    out = argv[1]
    curve = os.path.join(out, "trapdoor.png")
    plot_curves(runs, curve)
    print(curve)
    res = runs[0][2]
    B, H = res["door_width"], res["height"]
    fr = plot_cover.read_frame(os.path.join(out, "particles.h5"))
    shape = os.path.join(out, "trapdoor_deformed.png")
    d = runs[0][0][-1]
    plot_cover.plot_deformed(
        fr, [], f"trapdoor H/B = {H / B:g}, door lowered {100 * d:.1f} % of B (half model, "
        "x = 0 the door's centre line)", shape,
        window=(0.0, min(2.5 * B, res["soil_half_width"]), -0.05 * H - d * B, 1.02 * H))
    print(shape)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
