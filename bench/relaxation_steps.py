#!/usr/bin/python3
"""Relaxation that reaches its tolerance: steps to -tol as shipped (kinetic damping, chain points
every quarter cell) and with one chain point per cell (-chain_spacing 1), on the three cases that
stalled or crept; -chain_pic 0 on request (--schemes).

    /usr/bin/python3 bench/relaxation_steps.py              # ~1 h on 2 cores (the slope is most
                                                            # of it); rewrites the "Relaxation
                                                            # steps" section of BENCHMARKS.md
    /usr/bin/python3 bench/relaxation_steps.py --quick      # the catenary only, ~5 min; writes
                                                            # bench/out/relaxation_steps/ only
    /usr/bin/python3 bench/relaxation_steps.py --only catenary,landfill --schemes fire

Cases (each as shipped but for the cell size):
  catenary  options/catenary.opts at h = 0.0625 m, 1 rank (-tol 5e-4, cap 100,000 steps)
  landfill  options/landfill_friction.opts with its membrane a chain in contact (mu = 0.3 on both
            faces) at h = 0.25 mm, 2 ranks, ramp 2000 steps (-tol 1e-5)
  slope     options/cover_slope.opts at h = 0.25 m, 2 ranks (-tol 1e-3, cap 30,000 per stage)
The slope's stage 2 stall is diagnosed by hand (relaxation_steps.md, second section; checkpoints
compared by bench/relaxation_creep.py).
Per run: the steps of every stage, whether it reached -tol, the final ratio, wall time, and the
answers the tests read; the last column is each answer's relative change from the shipped (kinetic) run.
Every run writes its ratio history (-relax_history) to bench/out/relaxation_steps/<run>_history.csv.
"""
import argparse
import csv
import time
from pathlib import Path

from benchmarks_md import publish, run_pmpm

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "bench" / "out" / "relaxation_steps"
MARK_BEGIN, MARK_END = "<!-- relaxation_steps.py begin -->", "<!-- relaxation_steps.py end -->"

# "kinetic" is the default (the before); "spacing1" one chain point per cell (the after: the
# stalls are the chains' points sharing a cell, not the damping); "chainpic0" a damping-side
# alternative; "fire" is refused with chains (all three cases have one) and fails there
# (options/catenary.opts now ships -chain_spacing 1: all but "spacing1" name the default 0.25)
Q = ["-chain_spacing", 0.25]
SCHEMES = {"kinetic": ["-damping", "kinetic"] + Q, "spacing1": ["-chain_spacing", 1],
           "fire": ["-damping", "fire"] + Q, "chainpic0": ["-chain_pic", 0] + Q}

# case: (ranks, options, answers read from summary.json results or the last stages.csv row)
CASES = {
    "catenary": (1, ["-options_file", "options/catenary.opts", "-cell_size", 0.0625],
                 ["sag", "strain_mid", "strain_support", "horizontal_reaction"]),
    "landfill": (2, ["-options_file", "options/landfill_friction.opts", "-landfill_membrane_chain",
                     "-interface_type", "contact", "-cell_size", 0.00025, "-ramp_steps", 2000],
                 ["settlement_centre", "differential_settlement", "sag", "peak_axial_strain"]),
    # the gauge of bench/cover_refinement.py (the coarsest cell), so the strains compare
    "slope": (2, ["-options_file", "options/cover_slope.opts", "-cell_size", 0.25,
                  "-cover_strain_gauge", 1.0],
              ["peak_strain", "peak_tension", "differential_settlement", "max_slip"]),
}


def run(case, scheme):
    np_, args, keys = CASES[case]
    out = OUT / f"{case}_{scheme}"
    # beside the run's directory: pmpm opens the history before it makes its output directory
    hist_path = OUT / f"{case}_{scheme}_history.csv"
    s = run_pmpm(ROOT / "build" / "pmpm", np_,
                 args + SCHEMES[scheme] + ["-relax_history", hist_path], out,
                 timeout=7200)
    if s is None:
        return None
    stages = []
    if (out / "stages.csv").exists():
        with open(out / "stages.csv") as f:
            rows = list(csv.DictReader(f))
        stages = [(int(r["steps"]), r["converged"] == "1", float(r["ratio"])) for r in rows]
        answers = {k: float(rows[-1][k]) for k in keys}
    else:
        answers = {k: float(s["results"][k]) for k in keys}
        stages = [(int(s["steps"]), bool(s["converged"]), None)]
    ratio = None
    with open(hist_path) as f:
        hist = list(csv.DictReader(f))
    if hist:
        ratio = float(hist[-1]["ratio"])
    return dict(steps=int(s["steps"]), stages=stages, converged=bool(s["converged"]),
                wall=s["wall_seconds"], ratio=ratio, answers=answers)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="the catenary only")
    ap.add_argument("--only", default="", help="comma-separated cases: catenary,landfill,slope")
    ap.add_argument("--schemes", default="kinetic,spacing1",
                    help="comma-separated: " + ",".join(SCHEMES) + " (kinetic first: the base)")
    a = ap.parse_args()
    cases = ["catenary"] if a.quick else (a.only.split(",") if a.only else list(CASES))
    schemes = a.schemes.split(",")
    OUT.mkdir(parents=True, exist_ok=True)
    lines = [MARK_BEGIN, "## Relaxation steps (bench/relaxation_steps.py)", "",
             f"Generated {time.strftime('%Y-%m-%d %H:%M')} by `/usr/bin/python3 "
             "bench/relaxation_steps.py` on 2 cores shared with other jobs (wall times are "
             "indicative only). Steps per stage (`*`: stopped at the step cap, not converged); "
             "answers the tests read; change: the largest relative change of those answers from "
             "the shipped (kinetic) run.", "",
             "| case | scheme | steps per stage | total steps | all converged | final ratio | "
             "wall (s) | answers | change from shipped |",
             "|---|---|---|---|---|---|---|---|---|"]
    for case in cases:
        base = None
        for scheme in schemes:
            print(f"{case} / {scheme} ...", flush=True)
            r = run(case, scheme)
            if r is None:
                lines.append(f"| {case} | {scheme} | failed | | | | | | |")
                continue
            if scheme == "kinetic":
                base = r
            per = ", ".join(f"{n}{'' if ok else '*'}" for n, ok, _ in r["stages"])
            ans = ", ".join(f"{k} {v:.6g}" for k, v in r["answers"].items())
            change = ""
            if base is not None and scheme != "kinetic":
                change = f"{max(abs(v / base['answers'][k] - 1) if base['answers'][k] else abs(v) for k, v in r['answers'].items()):.2e}"
                change += f" ({base['steps'] / r['steps']:.1f}x fewer steps)"
            lines.append(f"| {case} | {scheme} | {per} | {r['steps']} | "
                         f"{'yes' if r['converged'] else 'no'} | "
                         f"{r['ratio']:.2e} | {r['wall']:.1f} | {ans} | {change} |")
            print(lines[-1], flush=True)
    lines += ["", MARK_END]
    full = not a.quick and not a.only and a.schemes == "kinetic,spacing1"
    publish("\n".join(lines) + "\n", OUT / "RELAXATION_STEPS.md", MARK_BEGIN, MARK_END, full)


if __name__ == "__main__":
    main()
