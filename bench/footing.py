#!/usr/bin/python3
"""The strip footing's capacity brackets (issue 11, docs/anti-locking.md): where the soil stops
finding equilibrium, against Prandtl's (2 + pi) k (von Mises) and Prandtl-Reissner's c N_c
(c-phi Drucker-Prager), with and without F-bar, at two cell sizes.

    /usr/bin/python3 bench/footing.py            # ~20 min on 2 cores; rewrites the "Strip
                                                 # footing" section of docs/benchmarks/footing.md
    /usr/bin/python3 bench/footing.py --quick    # h = B/16 only; bench/out/footing/ only

Each run loads pressure stages (fractions of the exact capacity) in one relaxation; a stage
"holds" when it reaches equilibrium (-tol 1e-3) before the footing settles 0.1 B, and the run
stops at the first that does not (options/footing.opts and footing_cphi.opts explain the
scene). The bracket is (largest that held, first that did not). 1 rank; the c-phi soil is 4.5 m
wide (Prandtl's mechanism reaches 3.03 B at phi = 20 deg), the von Mises soil 3 m (1.5 B).
Plain F-bar with the dilatant c-phi soil is refused by pmpm (docs/anti-locking.md): its row shows the refusal.
"""
import argparse
import math
from pathlib import Path

from benchmarks_md import error_line, launch, publish

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "bench" / "out" / "footing"
EXE = ROOT / "build" / "pmpm"
MARK_BEGIN, MARK_END = "<!-- footing.py begin -->", "<!-- footing.py end -->"

QU_VM = (2.0 + math.pi) * 17320.508 / math.sqrt(3.0)
PHI, COH = math.radians(20.0), 10e3
QU_CPHI = COH * (math.exp(math.pi * math.tan(PHI)) * math.tan(math.pi / 4 + PHI / 2) ** 2 - 1) \
    / math.tan(PHI)
FRACTIONS = (0.90, 0.95, 1.00, 1.05, 1.10, 1.15, 1.20)

# name: (options, extra arguments, exact capacity)
SOILS = {
    "von Mises": (["-options_file", "options/footing.opts"], [], QU_VM),
    "c-phi": (["-options_file", "options/footing_cphi.opts"],
              ["-footing_soil_width", "4.5", "-footing_soil_depth", "2.5"], QU_CPHI),
}
# variant: F-bar options
VARIANTS = {
    "F-bar": ["-fbar", "1", "-fbar_pressure", "particle"],
    "F-bar, cell pressure": ["-fbar", "1", "-fbar_pressure", "cell"],
    "no F-bar": ["-fbar", "0", "-fbar_pressure", "particle"],
}


def bracket(soil, variant, h):
    opts, extra, qu = SOILS[soil]
    pressures = ",".join(f"{f * qu:.6f}" for f in FRACTIONS)
    args = opts + extra + VARIANTS[variant] + [
        "-cell_size", repr(h), "-footing_collapse_settlement", "0.1", "-footing_pressures",
        pressures, "-tol", "1e-3", "-max_steps", "60000"]
    name = f"{soil}_{variant}_{h}".replace(" ", "_").replace(",", "")
    s, output = launch(EXE, 1, args, OUT / name)
    if s is None:
        line = error_line(output)
        if "-fbar_pressure cell" in line:
            return {"error": "unstable under dilatant flow without -fbar_pressure cell"}
        return {"error": line.split(": ", 2)[-1][:120]}
    r = s["results"]
    held = [st for st in r["stages"] if st["holds"]]
    failed = [st for st in r["stages"] if not st["holds"]]
    return {
        "held": held[-1]["pressure"] / qu if held else None,
        "settlement": held[-1]["settlement"] if held else None,
        "collapsed": failed[0]["pressure"] / qu if failed else None,
        "wall": s["wall_seconds"],
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="h = B/16 only; no docs/benchmarks/footing.md update")
    a = ap.parse_args()
    hs = (0.0625,) if a.quick else (0.0625, 0.03125)
    rows = []
    for soil in SOILS:
        for h in hs:
            for variant in VARIANTS:
                if soil == "von Mises" and variant == "F-bar, cell pressure" and h != 0.03125:
                    continue
                r = bracket(soil, variant, h)
                print(soil, variant, h, r, flush=True)
                rows.append((soil, h, variant, r))
    lines = [MARK_BEGIN, "## Strip footing (bench/footing.py)", "",
             "Capacity brackets in units of the exact capacity (von Mises: (2 + pi) k = "
             f"{QU_VM / 1e3:.2f} kPa; c-phi, phi = psi = 20 deg, c = 10 kPa: c N_c = "
             f"{QU_CPHI / 1e3:.2f} kPa); stages at "
             + ", ".join(f"{f:.2f}" for f in FRACTIONS) + " of it, 1 rank.", "",
             "| soil | h / B | F-bar | holds at (settlement) | collapses at | wall (s) |",
             "|---|---|---|---|---|---|"]
    for soil, h, variant, r in rows:
        if "error" in r:
            lines.append(f"| {soil} | 1/{round(1 / h)} | {variant} | refused: {r['error']} | | |")
            continue
        held = f"{r['held']:.2f} ({100 * r['settlement']:.1f} cm)" if r["held"] else "none"
        coll = f"{r['collapsed']:.2f}" if r["collapsed"] else "none (all held)"
        lines.append(f"| {soil} | 1/{round(1 / h)} | {variant} | {held} | {coll} | "
                     f"{r['wall']:.0f} |")
    lines += ["", "Command: `/usr/bin/python3 bench/footing.py`.", MARK_END]
    OUT.mkdir(parents=True, exist_ok=True)
    publish("\n".join(lines) + "\n", OUT / "footing.md", MARK_BEGIN, MARK_END, not a.quick)


if __name__ == "__main__":
    main()
