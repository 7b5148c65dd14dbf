#!/usr/bin/python3
"""Membrane chains (issue 8): what they cost, and what they cost scenes without them.

    /usr/bin/python3 bench/chains.py            # ~10 min on 2 cores; rewrites the "Membrane
                                                # chains" section of docs/benchmarks/chains.md
    /usr/bin/python3 bench/chains.py --quick    # seconds; writes bench/out/chains/CHAINS.md only

1. Scenes without chains pay nothing: the landfill and the column timed with this binary and with
   the parent revision's (the commit before bodies came to the grid, built once into
   bench/out/baseline-<rev>/), alternating runs, best of N, ms per step.
2. The seed landfill with its membrane as a chain beside the resolved membrane (bonded and
   frictional, h = 0.5 and 0.25 mm): steps, wall time, the answers.
3. Stress test: a stiff sheet on soft waste (J up to 1e7 N/m, waste E down to 0.5 MPa; the seed
   landfill with a chain, field unit weights): does it relax without instability, in how many
   steps.
"""
import argparse
import os
import shutil
import time
from pathlib import Path

from benchmarks_md import build_revision, publish, run_pmpm

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "bench" / "out" / "chains"
BASE_REV = "8d3e17d"  # the last commit with one velocity field per node and no chains
MARK_BEGIN, MARK_END = "<!-- chains.py begin -->", "<!-- chains.py end -->"


def run(exe, np_, args, out, timeout=3600):
    """Run pmpm; return its summary (with wall time) or None with the error printed."""
    return run_pmpm(exe, np_, args, out, timeout)


def baseline_binary(rev):
    """Build `rev` once into bench/out/baseline-<rev>/ (git worktree + cmake); its pmpm path."""
    return build_revision(rev, "baseline")


def table(header, rows):
    s = "| " + " | ".join(header) + " |\n|" + "---|" * len(header) + "\n"
    for r in rows:
        s += "| " + " | ".join(str(x) for x in r) + " |\n"
    return s


def overhead(exe, base, quick):
    """ms per step of scenes without chains, this binary against the baseline, best of N."""
    cases = [("landfill h = 0.5 mm", ["-options_file", "options/landfill.opts", "-max_steps",
                                       300 if quick else 1500, "-tol", "1e-300"], 2),
             ("column 64 cells", ["-options_file", "options/column.opts", "-cell_size",
                                  1 / 64, "-max_steps", 300 if quick else 3000, "-tol", "1e-300"],
              1)]
    reps = 1 if quick else 5
    rows = []
    for name, args, np_ in cases:
        best = {"new": 1e300, "base": 1e300}
        same = True
        for k in range(reps):
            for tag, b in (("new", exe), ("base", base)):
                s = run(b, np_, args, OUT / f"overhead_{tag}")
                if s is None:
                    return "overhead runs failed\n"
                best[tag] = min(best[tag], s["wall_seconds"] / s["steps"] * 1e3)
                if tag == "new":
                    new_res = s["results"]
                else:  # every number to 1e-10 relative (keys new in this binary aside)
                    same = same and all(
                        abs(v - new_res[k]) <= 1e-10 * max(abs(v), 1e-300)
                        for k, v in s["results"].items() if isinstance(v, float) and k in new_res)
        rows.append([name, np_, f"{best['base']:.3f}", f"{best['new']:.3f}",
                     f"{best['new'] / best['base']:.3f}", "same to 1e-10" if same else "differ"])
    return table(["scene (no chains)", "ranks", f"ms/step {BASE_REV}", "ms/step now", "ratio",
                  "results"], rows)


def landfill(exe, quick):
    hs = [0.001] if quick else [0.0005, 0.00025]
    rows = []
    for h in hs:
        ramp = int(round(1000 * 0.0005 / h))
        common = ["-cell_size", h, "-ramp_steps", ramp] + (["-tol", "1e-3"] if quick else [])
        cases = [
            ("resolved, bonded", ["-options_file", "options/landfill.opts"]),
            ("chain, bonded", ["-options_file", "options/landfill.opts",
                               "-landfill_membrane_chain", "-interface_type", "bonded"]),
            ("resolved, paper mu 0.3", ["-options_file", "options/landfill_friction.opts"]),
            ("chain, contact mu 0.3", ["-options_file", "options/landfill_friction.opts",
                                       "-landfill_membrane_chain", "-interface_type", "contact"]),
        ]
        for name, args in cases:
            s = run(exe, 2, args + common, OUT / f"landfill_{name.replace(' ', '_')}_{h}")
            if s is None:
                rows.append([f"{h * 1e3:g}", name, "failed"] + [""] * 7)
                continue
            r = s["results"]
            rows.append([f"{h * 1e3:g}", name, s["steps"], f"{s['wall_seconds']:.1f}",
                         "yes" if s["converged"] else "no",
                         f"{r['settlement_centre'] * 1e3:.3f}",
                         f"{r['differential_settlement'] * 1e3:.3f}", f"{r['sag'] * 1e3:.3f}",
                         f"{r['peak_axial_strain'] * 100:.2f}",
                         f"{r['peak_axial_strain_x'] * 1e3:.2f}"])
    return table(["h (mm)", "membrane", "steps", "wall (s)", "converged", "settlement (mm)",
                  "differential (mm)", "sag (mm)", "peak strain (%)", "at x (mm)"], rows)


def stiff_sheet(exe, quick):
    """The seed landfill with its membrane a chain, field-like unit weights (soil 20, waste 10
    kN/m^3) so that soft waste stays in small strain, the sheet's J and the waste's E varied."""
    Js = [1e5, 1e7] if quick else [1e5, 1e6, 1e7]
    Es = [5e6] if quick else [5e6, 0.5e6]
    rows = []
    for E in Es:
        for J in Js:
            t = 0.001
            args = ["-options_file", "options/landfill.opts", "-landfill_membrane_chain",
                    "-interface_type", "contact", "-interface_mu_top", "0.5",
                    "-interface_mu_bottom", "0.5", "-mat_membrane_E", J / t,
                    "-mat_membrane_axial_stiffness", "uniaxial", "-mat_soil_gamma", 2e4,
                    "-mat_waste_gamma", 1e4, "-mat_soft_gamma", 1e4, "-mat_membrane_gamma", 9.4e3,
                    "-mat_waste_E", E, "-mat_soft_E", E / 10, "-cell_size", 0.001 if quick else
                    0.0005, "-tol", 1e-4, "-max_steps", 3000 if quick else 60000]
            s = run(exe, 2, args, OUT / f"stiff_{J:g}_{E:g}")
            if s is None:
                rows.append([f"{J:g}", f"{E / 1e6:g}", "instability or error", "", "", ""])
                continue
            c = s["chains"]["membrane"]
            rows.append([f"{J:g}", f"{E / 1e6:g}", s["steps"], "yes" if s["converged"] else "no",
                         f"{s['unbalanced_force_ratio']:.1e}", f"{s['wall_seconds']:.1f}",
                         f"{s['results']['settlement_centre'] * 1e6:.2f}",
                         f"{c['peak_strain'] * 100:.2e}"])
    return table(["J (N/m)", "waste E (MPa)", "steps", "converged (1e-4)", "ratio", "wall (s)",
                  "settlement (um)", "peak strain (%)"], rows)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--baseline", default=BASE_REV)
    a = ap.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    exe_src = ROOT / "build" / "pmpm"
    exe = OUT / "pmpm"
    shutil.copy2(exe_src, exe)  # a snapshot: a rebuild during the study does not mix versions
    md = [MARK_BEGIN, "## Membrane chains (bench/chains.py)", "",
          f"Generated {time.strftime('%Y-%m-%d %H:%M')} by `/usr/bin/python3 bench/chains.py"
          f"{' --quick' if a.quick else ''}` on {os.cpu_count()} cores.", ""]
    print("1. scenes without chains: this binary against", a.baseline)
    base = baseline_binary(a.baseline)
    md += ["### Scenes without chains pay nothing", "",
           f"Best of 5 alternating runs, fixed step counts; `{a.baseline}` is the revision before "
           "bodies came to the grid (one velocity block per node, no chain code). A ratio within "
           "the runs' spread (a few per cent on this machine) is no cost.", "",
           overhead(exe, base, a.quick)]
    print("2. the landfill's membrane as a chain")
    md += ["### The seed landfill: resolved membrane against a chain", "",
           "Load II, 2 ranks; the chain lies on top of the 1 mm membrane layer, which is given to "
           "the waste (docs/landfill.md).", "", landfill(exe, a.quick)]
    print("3. stiff sheet on soft waste")
    md += ["### Stress test: a stiff sheet on soft waste", "",
           "The seed landfill with its membrane a chain (contact, mu = 0.5), field unit weights "
           "(soil 20, waste 10 kN/m^3), h = 0.5 mm, -tol 1e-4, at most 60,000 steps, the sheet's J and "
           "the waste's E varied (the "
           "soft zone E / 10); the sheet's inertia is scaled to the continuum's wave speed, so "
           "its stiffness does not set the step.", "", stiff_sheet(exe, a.quick), MARK_END]
    text = "\n".join(md) + "\n"
    publish(text, OUT / "CHAINS.md", MARK_BEGIN, MARK_END, not a.quick)


if __name__ == "__main__":
    main()
