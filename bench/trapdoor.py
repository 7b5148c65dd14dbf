#!/usr/bin/python3
"""The active trapdoor's ground reaction curve (issue 11): the pressure on the door over gamma H
against the door's displacement over B, for H/B = 1, 2, 3, beside Terzaghi's arching with K = 1
and K = Ka (docs/method.md, section 6.4); then how the curve's minimum moves with the door's rate and the cell.

    /usr/bin/python3 bench/trapdoor.py          # ~25 min on 2 cores; writes bench/out/trapdoor/
                                                # (TRAPDOOR.md, the runs), bench/trapdoor.png,
                                                # bench/trapdoor_deformed.png and its section
                                                # of docs/benchmarks/trapdoor.md
    /usr/bin/python3 bench/trapdoor.py --quick  # H/B = 1 only, no rate or cell study
    /usr/bin/python3 bench/trapdoor.py --reuse  # tables and pictures from the runs already made

options/trapdoor.opts (phi 30 deg, psi 0, c = 0, E 20 MPa, nu 0.3, 18 kN/m^3, B = 1 m), half
model, soil half-width 2.5 B (2 B beyond the door's edge), h = B/16, the door lowered at
-trapdoor_rate (cells per step) through the stages below, each relaxed to -tol 1e-4. Two runs
at a time, one rank each.
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
import closed_forms as cf  # noqa: E402
from benchmarks_md import MPI_ENV, publish  # noqa: E402

OUT = ROOT / "bench" / "out" / "trapdoor"
MARK_BEGIN, MARK_END = "<!-- trapdoor.py begin -->", "<!-- trapdoor.py end -->"
CURVE = "0.001,0.002,0.005,0.01,0.015,0.02,0.03,0.05,0.075,0.1"
SHORT = "0.002,0.005,0.01,0.02,0.03"  # the rate and cell studies: the minimum only
SHORT2 = "0.002,0.005,0.01,0.02,0.05,0.1"  # H/B = 2 on the coarse grid, with and without F-bar
PHI, B = 30.0, 1.0


def git_rev():
    p = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                       stdout=subprocess.PIPE, text=True)
    return p.stdout.strip() or "?"


def run(name, hb, h, rate, disp, extra=(), reuse=False):
    d = OUT / name
    if reuse and (d / "summary.json").is_file():
        return result(name, hb, h, rate, d, extra)
    if d.is_dir():
        shutil.rmtree(d)
    cmd = ["mpiexec", "-n", "1", str(OUT / "bin" / "pmpm"), "-options_file",
           "options/trapdoor.opts", "-cell_size", str(h), "-trapdoor_height", str(hb * B),
           "-trapdoor_soil_width", str(2.5 * B), "-trapdoor_rate", str(rate),
           "-trapdoor_displacements", disp, "-max_steps", "400000", "-output_dir", str(d),
           "-quiet", *extra]
    p = subprocess.run(cmd, env=MPI_ENV, cwd=ROOT, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True)
    if p.returncode != 0:
        print(p.stdout[-1500:])
        sys.exit(f"pmpm failed: {name}")
    return result(name, hb, h, rate, d, extra)


def result(name, hb, h, rate, d, extra):
    with open(d / "summary.json") as f:
        s = json.load(f)
    r = s["results"]
    with open(d / "trapdoor.csv") as f:
        rows = list(csv.DictReader(f))
    print(f"  {name}: min {r['min_ratio']:.4f} at {100 * r['min_displacement_over_B']:.2f} % B, "
          f"final {r['final_ratio']:.4f}, {s.get('wall_seconds', 0):.0f} s", flush=True)
    return dict(name=name, hb=hb, h=h, rate=rate, res=r, rows=rows, dir=d,
                wall=s.get("wall_seconds", 0), extra=" ".join(extra))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--reuse", action="store_true",
                    help="read the runs already in bench/out/trapdoor instead of running them")
    a = ap.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    # every run uses the same build, copied at the start (a rebuild meanwhile does not mix in)
    (OUT / "bin").mkdir(exist_ok=True)
    shutil.copy2(ROOT / "build" / "pmpm", OUT / "bin" / "pmpm")
    h, rate = B / 16, 1e-5
    fb = ("-fbar",)
    jobs = [("hb1", 1, h, rate, CURVE)]
    if not a.quick:
        jobs += [("hb2", 2, h, rate, CURVE), ("hb3", 3, h, rate, CURVE),
                 ("hb1_fbar", 1, h, rate, CURVE, fb), ("hb2_fbar", 2, h, rate, CURVE, fb),
                 ("rate1e-4", 1, h, 1e-4, SHORT), ("rate3e-5", 1, h, 3e-5, SHORT),
                 ("h8", 1, B / 8, rate, SHORT), ("h8_fbar", 1, B / 8, rate, SHORT, fb),
                 ("hb2_h8", 2, B / 8, 3e-5, SHORT2), ("hb2_h8_fbar", 2, B / 8, 3e-5, SHORT2, fb)]
    with ThreadPoolExecutor(max_workers=2) as ex:
        res = list(ex.map(lambda j: run(*j, reuse=a.reuse), jobs))
    curves = [r for r in res if r["name"].startswith("hb") and "h8" not in r["name"]]
    subprocess.run([sys.executable, str(ROOT / "scripts" / "plot_trapdoor.py"),
                    *[str(r["dir"]) for r in curves]], check=True)
    # the pictures docs/benchmarks/ and docs/trapdoor.md show live in bench/ (bench/out is not kept)
    shutil.copy(curves[0]["dir"] / "trapdoor.png", ROOT / "bench" / "trapdoor.png")
    shutil.copy(curves[0]["dir"] / "trapdoor_deformed.png",
                ROOT / "bench" / "trapdoor_deformed.png")

    def terz(hb, K):
        return cf.terzaghi_arching(1.0, B, hb * B, K, PHI) / (hb * B)

    ka = (1 - math.sin(math.radians(PHI))) / (1 + math.sin(math.radians(PHI)))
    md = [MARK_BEGIN, "## Active trapdoor: ground reaction curve (bench/trapdoor.py)", "",
          "options/trapdoor.opts (phi 30 deg, psi 0, c = 0, plane-strain-matched Drucker-Prager, "
          "E 20 MPa, nu 0.3, 18 kN/m^3), B = 1 m, half model 2.5 B wide, one rank. p: the door's "
          "force over its width; Terzaghi (docs/method.md, section 6.4, c = q = 0) with K = 1 and K = Ka = "
          f"{ka:.3f}. Door rate in cells per step; h in B. Binary of git "
          f"{git_rev()}; command: `/usr/bin/python3 bench/trapdoor.py` (two runs at a time on "
          "the 2-core machine, shared; wall times are under that load).", "",
          "| H/B | h | rate | F-bar | p/(gamma H) at 0.2 % B | minimum | at (% B) | last "
          "(% B) | Terzaghi K = 1 | Terzaghi K = Ka | stages not converged | wall (s) |",
          "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in res:
        rr = r["res"]
        p02 = [float(x["pressure_over_gammaH"]) for x in r["rows"]
               if abs(float(x["displacement_over_B"]) - 0.002) < 1e-9]
        md.append(f"| {r['hb']} | 1/{round(B / r['h'])} | {r['rate']:g} | "
                  f"{'yes' if '-fbar' in r['extra'] else 'no'} | "
                  f"{p02[0] if p02 else float('nan'):.3f} | {rr['min_ratio']:.3f} | "
                  f"{100 * rr['min_displacement_over_B']:.1f} | {rr['final_ratio']:.3f} "
                  f"({100 * rr['final_displacement_over_B']:.1f}) | {terz(r['hb'], 1):.3f} | "
                  f"{terz(r['hb'], ka):.3f} | "
                  f"{sum(not x['converged'] for x in rr['stages']) or ''} | {r['wall']:.0f} |")
    md += ["", "The curves (H/B = 1, 2, 3; dashed: Terzaghi K = 1, dotted: K = Ka):", "",
           "![trapdoor curves](bench/trapdoor.png)", "",
           f"H/B = {curves[0]['hb']} at the last stage, particles filled by eps_p:", "",
           "![trapdoor deformed](bench/trapdoor_deformed.png)", "", MARK_END]
    text = "\n".join(md)
    publish(text, OUT / "TRAPDOOR.md", MARK_BEGIN, MARK_END, not a.quick)


if __name__ == "__main__":
    main()
