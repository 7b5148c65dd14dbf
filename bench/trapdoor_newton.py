#!/usr/bin/python3
"""The active trapdoor under Newton (issue 24): the ground reaction curve with the door's
displacement imposed in load steps (quasi-static, no rate), beside relaxation's rate series.

    /usr/bin/python3 bench/trapdoor_newton.py          # writes bench/out/trapdoor_newton/
                                                       # (TRAPDOOR_NEWTON.md, the runs),
                                                       # bench/trapdoor_newton.png and its section
                                                       # of docs/benchmarks/trapdoor.md
    /usr/bin/python3 bench/trapdoor_newton.py --quick  # H/B = 1 at h = B/16 only
    /usr/bin/python3 bench/trapdoor_newton.py --reuse  # reuse the runs made, run the others
    /usr/bin/python3 bench/trapdoor_newton.py --no-run # table and picture of the runs made only

options/trapdoor.opts (phi 30 deg, psi 0, c = 0, E 20 MPa, nu 0.3, 18 kN/m^3, B = 1 m), half
model, soil half-width 2.5 B, the stages of bench/trapdoor.py's curve (0.1 ... 10 % of B; H/B = 2
to 5 %) under
-solver newton with N load steps a stage (-newton_load_steps N), each stage closed by Newton's
equilibrium steps to -tol 1e-4. Every case runs at N = 10 and N = 20 (each load step halved):
a quasi-static answer must not move with the step. Relaxation's curves (bench/trapdoor.py, door
lowered at -trapdoor_rate cells per step) are quoted from docs/benchmarks/trapdoor.md, not rerun.
One rank, two runs at a time.
"""
import argparse
import csv
import json
import math
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "bench"))
import closed_forms as cf  # noqa: E402
from benchmarks_md import MPI_ENV  # noqa: E402

OUT = ROOT / "bench" / "out" / "trapdoor_newton"
MARK_BEGIN, MARK_END = "<!-- trapdoor_newton.py begin -->", "<!-- trapdoor_newton.py end -->"
CURVE = "0.001,0.002,0.005,0.01,0.015,0.02,0.03,0.05,0.075,0.1"
SHORT = "0.001,0.002,0.005,0.01,0.015,0.02,0.03"  # the finer mesh: the fall and the minimum
SHORT2 = "0.001,0.002,0.005,0.01,0.02,0.03,0.05"  # H/B = 2: to 5 % of B
PHI, B = 30.0, 1.0
# Relaxation (docs/benchmarks/trapdoor.md, bench/trapdoor.py, h = B/16, no F-bar): per H/B and door
# rate (cells per step) the points that table gives: (displacement / B, p / gamma H) at 0.2 % B,
# at the minimum and at the last stage.
RELAX = {1: {1e-4: [(0.002, 0.665), (0.03, 0.704)],
             3e-5: [(0.002, 0.623), (0.005, 0.591), (0.03, 0.598)],
             1e-5: [(0.002, 0.604), (0.01, 0.561), (0.1, 0.589)]},
         2: {1e-5: [(0.002, 0.426), (0.1, 0.235)]}}
RELAX_MIN = {1: {1e-4: 0.665, 3e-5: 0.591, 1e-5: 0.561}, 2: {1e-5: 0.235}}


def git_rev():
    p = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                       stdout=subprocess.PIPE, text=True)
    return p.stdout.strip() or "?"


def run(name, hb, h, steps, disp, reuse=False):
    d = OUT / name
    if reuse == "only" and not (d / "trapdoor.csv").is_file():
        print(f"  {name}: not run (--no-run)")
        return None
    if not (reuse and (d / "summary.json").is_file()) and reuse != "only":
        if d.is_dir():
            shutil.rmtree(d)
        cmd = ["mpiexec", "-n", "1", str(OUT / "bin" / "pmpm"), "-options_file",
               "options/trapdoor.opts", "-cell_size", str(h), "-trapdoor_height", str(hb * B),
               "-trapdoor_soil_width", str(2.5 * B), "-trapdoor_displacements", disp,
               "-solver", "newton", "-newton_load_steps", str(steps), "-output_dir", str(d),
               "-max_steps", "400000"]
        with open(d.parent / f"{name}.log", "w") as log:  # a file: the run outlives this script
            p = subprocess.run(cmd, env=MPI_ENV, cwd=ROOT, stdout=log, stderr=subprocess.STDOUT)
        if p.returncode not in (0, 3):  # 3: a stage ended NOT converged, its answers written
            sys.exit(f"pmpm failed: {name} (see {d.parent / (name + '.log')})")
    # the curve from trapdoor.csv (written after every stage: a run stopped early gives its
    # stages so far); wall time and Newton's counts from summary.json when the run finished
    with open(d / "trapdoor.csv") as f:
        rows = list(csv.DictReader(f))
    s = {}
    if (d / "summary.json").is_file():
        with open(d / "summary.json") as f:
            s = json.load(f)
    dd = [float(x["displacement_over_B"]) for x in rows]
    pp = [float(x["pressure_over_gammaH"]) for x in rows]
    ok = [i for i in range(1, len(pp)) if int(rows[i]["converged"])]  # stages in equilibrium
    k = min(ok, key=lambda i: pp[i])
    r = dict(min_ratio=pp[k], min_displacement_over_B=dd[k], final_ratio=pp[ok[-1]],
             final_displacement_over_B=dd[ok[-1]])
    print(f"  {name}: min {r['min_ratio']:.4f} at {100 * r['min_displacement_over_B']:.2f} % B, "
          f"final {r['final_ratio']:.4f}, {s.get('wall_seconds', float('nan')):.1f} s",
          flush=True)
    return dict(name=name, hb=hb, h=h, steps=steps, res=r, dir=d, finished=bool(s),
                wall=s.get("wall_seconds", float("nan")), newton=s.get("newton", {}), d=dd, p=pp,
                conv=[int(x["converged"]) for x in rows])


def terz(hb, K):
    return cf.terzaghi_arching(1.0, B, hb * B, K, PHI) / (hb * B)


def plot(res, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    ka = (1 - math.sin(math.radians(PHI))) / (1 + math.sin(math.radians(PHI)))
    for ax, hb in zip(axes, (1, 2)):
        for r in res:
            if r["hb"] != hb:
                continue
            style = "-" if r["steps"] == 10 else "--"
            col = "k" if round(B / r["h"]) == 16 else "C3"
            ok = [(100 * x, y) for x, y, c in zip(r["d"], r["p"], r["conv"]) if c]
            ax.plot([x for x, _ in ok], [y for _, y in ok], style, color=col, marker="o", ms=3,
                    label=f"Newton, h = B/{round(B / r['h'])}, {r['steps']} load steps a stage")
            bad = [(100 * x, y) for x, y, c in zip(r["d"], r["p"], r["conv"]) if not c]
            if bad:  # a stage whose load steps stalled: where its last converged step left it
                ax.plot([x for x, _ in bad], [y for _, y in bad], "x", color=col, ms=7)
        for k, (rate, pts) in enumerate(sorted(RELAX.get(hb, {}).items(), reverse=True)):
            ax.plot([0] + [100 * x for x, _ in pts], [1.0] + [y for _, y in pts], ":",
                    marker="s", ms=4, color=f"C{k}",
                    label=f"relaxation, h = B/16, rate {rate:g} cells/step (table points)")
        ax.axhline(terz(hb, 1.0), color="grey", ls="--", lw=0.8, label="Terzaghi K = 1")
        ax.axhline(terz(hb, ka), color="grey", ls=":", lw=0.8, label="Terzaghi K = Ka")
        ax.set_xscale("symlog", linthresh=0.1)
        ax.set_xlim(0, 10.5)
        ax.set_xlabel("door displacement (% of B)")
        ax.set_ylabel("p / (gamma H)")
        ax.set_title(f"H/B = {hb}")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--reuse", action="store_true",
                    help="read the runs already in bench/out/trapdoor_newton, run the others")
    ap.add_argument("--no-run", action="store_true",
                    help="the table and picture of the runs already made only")
    ap.add_argument("--fine", action="store_true", help="also H/B = 1 at h = B/32")
    a = ap.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "bin").mkdir(exist_ok=True)
    if not (a.reuse or a.no_run) or not (OUT / "bin" / "pmpm").is_file():
        shutil.copy2(ROOT / "build" / "pmpm", OUT / "bin" / "pmpm")
    jobs = [("hb1_n10", 1, B / 16, 10, CURVE), ("hb1_n20", 1, B / 16, 20, CURVE)]
    if not a.quick:
        jobs += [("hb2_n10", 2, B / 16, 10, SHORT2), ("hb2_n20", 2, B / 16, 20, SHORT2)]
    if a.fine:
        jobs += [("hb1_h32_n10", 1, B / 32, 10, SHORT), ("hb1_h32_n20", 1, B / 32, 20, SHORT)]
    with ThreadPoolExecutor(max_workers=2) as ex:
        reuse = "only" if a.no_run else a.reuse
        res = [r for r in ex.map(lambda j: run(*j, reuse=reuse), jobs) if r]
    plot(res, ROOT / "bench" / "trapdoor_newton.png")
    ka = (1 - math.sin(math.radians(PHI))) / (1 + math.sin(math.radians(PHI)))
    md = [MARK_BEGIN, "## The trapdoor under Newton: the curve without a rate "
          "(bench/trapdoor_newton.py)", "",
          "Same soil, door and stages as above (options/trapdoor.opts, half model 2.5 B wide, "
          "one rank), under `-solver newton`: each stage imposes the door's displacement in "
          "`-newton_load_steps` N equal load steps (Dirichlet rows on the door's nodes, "
          "docs/newton.md, \"Moving supports\"), then equilibrium steps to -tol 1e-4; the door's "
          "pressure is the residual's force on the door's dofs. N = 20 halves every load step of "
          "N = 10: the difference is the largest |p_10 - p_20| / (gamma H) over the stages. "
          f"Binary of git {git_rev()}; command: `/usr/bin/python3 bench/trapdoor_newton.py"
          f"{' --fine' if a.fine else ''}` (two runs at a time on the shared 2-core machine).", "",
          "| H/B | h | N | p/(gamma H) at 0.1 % B | at 0.2 % B | minimum | at (% B) | last (% B) "
          "| max diff N = 10 vs 20 | Terzaghi K = 1 | K = Ka | relaxation minimum (rate) "
          "| stages not converged | load steps / Newton its | wall (s) |",
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    by = {(r["hb"], r["h"], r["steps"]): r for r in res}
    for r in res:
        rr = r["res"]
        other = by.get((r["hb"], r["h"], 30 - r["steps"]))
        # over the stages both runs converged at the same displacement
        both = [abs(x - y) for x, y, dx, dy, cx, cy in
                zip(r["p"], other["p"], r["d"], other["d"], r["conv"], other["conv"])
                if cx and cy and abs(dx - dy) < 1e-9] if other else []
        diff = max(both) if both else float("nan")
        at = {round(x, 6): y for x, y in zip(r["d"], r["p"])}
        rel = RELAX_MIN.get(r["hb"], {}) if round(B / r["h"]) == 16 else {}
        rels = ", ".join(f"{v:.3f} ({k:g})" for k, v in sorted(rel.items(), reverse=True))
        nw = r["newton"]
        wall = f"{r['wall']:.0f}" if r["finished"] else "- (stopped early)"
        md.append(f"| {r['hb']} | 1/{round(B / r['h'])} | {r['steps']} | "
                  f"{at.get(0.001, float('nan')):.3f} | {at.get(0.002, float('nan')):.3f} | "
                  f"{rr['min_ratio']:.3f} | {100 * rr['min_displacement_over_B']:.1f} | "
                  f"{rr['final_ratio']:.3f} ({100 * rr['final_displacement_over_B']:.1f}) | "
                  f"{diff:.1e} | {terz(r['hb'], 1):.3f} | {terz(r['hb'], ka):.3f} | "
                  f"{rels or '-'} | {sum(1 - c for c in r['conv']) or ''} | "
                  f"{nw.get('load_steps', '-')} / {nw.get('nonlinear_iterations', '-')} | "
                  f"{wall} |")
    md += ["", "Newton's curves (solid N = 10, dashed N = 20; x: a stage not converged, at the door "
           "displacement its last converged load step reached) beside relaxation's rate series "
           "(dotted: the points docs/benchmarks/trapdoor.md's table gives, joined; not rerun); "
           "grey: Terzaghi K = 1 (dashed) and K = Ka (dotted):", "",
           "![trapdoor under Newton](bench/trapdoor_newton.png)", "", MARK_END]
    text = "\n".join(md)
    (OUT / "TRAPDOOR_NEWTON.md").write_text(text + "\n")
    print(text)
    if not a.quick:  # its section of docs/benchmarks/trapdoor.md, after bench/trapdoor.py's
        doc = ROOT / "docs" / "benchmarks" / "trapdoor.md"
        old = doc.read_text()
        text = text.replace("](bench/", "](../../bench/")
        if MARK_BEGIN in old and MARK_END in old:
            new = old[:old.index(MARK_BEGIN)] + text + old[old.index(MARK_END) + len(MARK_END):]
        else:
            new = old.rstrip("\n") + "\n\n" + text + "\n"
        doc.write_text(new)
        print(f"updated {doc.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
