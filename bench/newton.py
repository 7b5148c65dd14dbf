#!/usr/bin/python3
"""Implicit Newton (-solver newton) against dynamic relaxation: time to equilibrium and error.

    /usr/bin/python3 bench/newton.py           # ~5 min on 2 cores; rewrites the "Implicit solver"
                                               # section of BENCHMARKS.md and bench/newton.png
    /usr/bin/python3 bench/newton.py --quick   # seconds; writes bench/out/newton/NEWTON.md only

1. The column under self-weight (options/column.opts, linear elastic, and column_large.opts,
   neo-Hookean at 26 % compression) at 16, 32, 64 and 128 cells over the height, each solver to
   the options file's -tol (unbalanced-force ratio 1e-7): wall time of the solve (summary.json
   wall_seconds), explicit steps or load steps / Newton / linear iterations, and the errors
   against the exact solutions.
2. The linear solver under Newton on the largest problem at hand, the bonded landfill at
   h = 0.5 mm (options/landfill.opts, 60 x 80 cells, 18,720 particles, about 9,800 unknowns):
   MUMPS LU (default AMD ordering, and METIS by -mat_mumps_icntl_7 5), GMRES with GAMG and with
   hypre BoomerAMG, beside relaxation.
One rank each (the study is the method's cost, not its parallel speed-up).
"""
import argparse
from pathlib import Path

from benchmarks_md import publish, run_pmpm

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "bench" / "out" / "newton"
EXE = ROOT / "build" / "pmpm"
MARK_BEGIN, MARK_END = "<!-- newton.py begin -->", "<!-- newton.py end -->"


def run(args, out, np_=1, timeout=3600):
    """Run pmpm; return its summary (with the launch's elapsed seconds) or None."""
    return run_pmpm(EXE, np_, args, out, timeout)


def work(s):
    """Steps (relaxation) or load steps / Newton / linear iterations (Newton)."""
    if s.get("solver") == "newton":
        n = s["newton"]
        return f"{n['load_steps']} / {n['nonlinear_iterations']} / {n['linear_iterations']}"
    return f"{s['steps']} steps"


# Newton's adaptive load steps: the body moves at most this fraction of a cell per step (the
# particle-path error of a load step is first order in it); the large column only to 64 cells
# (at 128 cells it settles 17 cells: 1,700 steps)
ADAPTIVE = {"column": (0.001, 128), "column_large": (0.01, 64)}


def column_study(cells, quick):
    rows = []
    for opts, label in (("column", "small strain"), ("column_large", "neo-Hookean, 26 %")):
        frac, upto = ADAPTIVE[opts]
        for n in cells:
            h = 1.0 / n
            variants = [("relaxation", []), ("newton", [])]
            if n <= upto:
                variants.append((f"newton, cell fraction {frac}",
                                 ["-newton_cell_fraction", frac]))
            for solver, extra in variants:
                d = OUT / f"{opts}_{n}_{solver.replace(' ', '_').replace(',', '')}"
                s = run(["-options_file", f"options/{opts}.opts", "-cell_size", h, "-solver",
                         solver.split(",")[0], "-max_steps", 400000] + extra, d)
                if s is None:
                    continue
                r = s["results"]
                rows.append(dict(case=label, opts=opts, cells=n, solver=solver,
                                 seconds=s["wall_seconds"], work=work(s), conv=s["converged"],
                                 ratio=s["unbalanced_force_ratio"],
                                 stress=r["stress_l2_error_rel"],
                                 disp=r["displacement_l2_error_rel"]))
                print(f"  {opts} {n} cells {solver}: {s['wall_seconds']:.3f} s, {work(s)}, "
                      f"stress {r['stress_l2_error_rel']:.4g}, disp "
                      f"{r['displacement_l2_error_rel']:.4g}", flush=True)
    return rows


def landfill_study():
    rows = []
    cases = [("relaxation", ["-solver", "relaxation"]),
             ("Newton, MUMPS LU (AMD)", ["-solver", "newton"]),
             ("Newton, MUMPS LU (METIS)", ["-solver", "newton", "-mat_mumps_icntl_7", 5]),
             ("Newton, GMRES + GAMG", ["-solver", "newton", "-ksp_type", "gmres", "-pc_type",
                                       "gamg", "-ksp_rtol", 1e-10]),
             ("Newton, GMRES + hypre", ["-solver", "newton", "-ksp_type", "gmres", "-pc_type",
                                        "hypre", "-ksp_rtol", 1e-10])]
    for k, (label, extra) in enumerate(cases):
        s = run(["-options_file", "options/landfill.opts"] + extra, OUT / f"landfill_{k}")
        if s is None:
            continue
        r = s["results"]
        rows.append(dict(label=label, seconds=s["wall_seconds"], work=work(s), conv=s["converged"],
                         ratio=s["unbalanced_force_ratio"], settle=r["settlement_centre"],
                         strain=r["peak_axial_strain"]))
        print(f"  landfill {label}: {s['wall_seconds']:.2f} s, {work(s)}", flush=True)
    return rows


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for i, opts in enumerate(("column", "column_large")):
        labels = list(dict.fromkeys(r["solver"] for r in rows if r["opts"] == opts))
        for solver, mk in zip(labels, ("o-", "s-", "^--")):
            pts = [(r["cells"], r["seconds"]) for r in rows
                   if r["opts"] == opts and r["solver"] == solver]
            if pts:
                ax[i].loglog(*zip(*pts), mk, label=solver)
        ax[i].set_title(f"options/{opts}.opts")
        ax[i].set_xlabel("cells over the height")
        ax[i].set_ylabel("wall time to equilibrium (s)")
        ax[i].grid(True, which="both", alpha=0.3)
        ax[i].legend()
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    print(f"wrote {path}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    cells = (16, 32) if a.quick else (16, 32, 64, 128)
    rows = column_study(cells, a.quick)
    lrows = [] if a.quick else landfill_study()
    png = ROOT / "bench" / "newton.png" if not a.quick else OUT / "newton.png"
    plot(rows, png)
    md = [MARK_BEGIN, "## Implicit solver: Newton against relaxation (bench/newton.py)", "",
          "One rank; wall time of the solve to the options file's -tol (unbalanced-force ratio "
          "1e-7 for the columns, 1e-5 for the landfill, the same test for both solvers); work is "
          "explicit steps, or load steps / Newton iterations / linear iterations (10 load steps, "
          "or as many as -newton_cell_fraction asks, then equilibrium steps on the reset grid). "
          "Errors: L2 against the exact solution (REFERENCE.md 2.2).", "",
          "| column | cells | solver | seconds | work | converged | stress error | "
          "displacement error |", "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        md.append(f"| {r['case']} | {r['cells']} | {r['solver']} | {r['seconds']:.3f} | "
                  f"{r['work']} | {'yes' if r['conv'] else 'NO'} | {r['stress']:.4g} | "
                  f"{r['disp']:.4g} |")
    md += ["", "![time to equilibrium](bench/newton.png)", ""]
    if lrows:
        md += ["Bonded landfill, h = 0.5 mm (options/landfill.opts; converged reference: "
               "settlement 2.958 mm, peak membrane strain 1.76 %, README):", "",
               "| solver | seconds | work | converged | settlement at X = 15 mm (mm) | "
               "peak membrane strain (%) |", "|---|---|---|---|---|---|"]
        for r in lrows:
            md.append(f"| {r['label']} | {r['seconds']:.2f} | {r['work']} | "
                      f"{'yes' if r['conv'] else 'NO'} | {r['settle'] * 1e3:.4f} | "
                      f"{r['strain'] * 100:.3f} |")
        md.append("")
    md.append(MARK_END)
    publish("\n".join(md) + "\n", OUT / "NEWTON.md", MARK_BEGIN, MARK_END, not a.quick)


if __name__ == "__main__":
    main()
