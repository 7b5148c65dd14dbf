#!/usr/bin/python3
"""Veneer stability of the slope example (issue 9): the friction angle at which the cover starts
to slide on the sheet, found by bisection, beside the infinite-slope and Koerner-Soong values.

    /usr/bin/python3 bench/cover_veneer.py          # ~5 min on 2 cores; writes
                                                    # bench/out/cover_veneer/VENEER.md and its
                                                    # section of docs/benchmarks/cover_veneer.md
    /usr/bin/python3 bench/cover_veneer.py --cohesion 0   # the cohesionless cover (Koerner-Soong's
                                                          # assumption; tests/test_cover_veneer.py)
    /usr/bin/python3 bench/cover_veneer.py --quick  # three angles, no bisection

options/cover_slope.opts without its degradation stages (stage 0 only: the veneer under its own
weight), the sheet's lower face held (delta 40 deg on the waste), its upper face at delta. A run
"holds" when stage 0 converges with the cover's slip on the sheet below 5 cm; otherwise the cover
slides (the run hits its step cap with the slip growing). The bisection brackets the threshold
delta to 0.25 deg. The closed forms (docs/method.md, section 6.3, tests/closed_forms.py): the infinite slope
slides below delta = beta; Koerner and Soong's finite slope, with its passive toe wedge, holds down
to the delta where FS = 1 (the wedge helps, so lower). pmpm's threshold is expected near the
Koerner-Soong value; the difference is reported, not asserted (a limit-equilibrium estimate with
assumed wedge shapes, against a continuum with Drucker-Prager soil).
"""
import argparse
import csv
import json
import math
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))
import closed_forms as cf  # noqa: E402
from benchmarks_md import MPI_ENV, publish  # noqa: E402

OUT = ROOT / "bench" / "out" / "cover_veneer"
SLIP_LIMIT = 0.05  # m
MARK_BEGIN, MARK_END = "<!-- cover_veneer.py begin -->", "<!-- cover_veneer.py end -->"


def holds(delta, h, np_, cohesion):
    d = OUT / f"delta_{delta:.3f}_h{h}"
    if d.is_dir():
        shutil.rmtree(d)
    cmd = ["mpiexec", "-n", str(np_), str(ROOT / "build" / "pmpm"), "-options_file",
           "options/cover_slope.opts", "-cover_shrink_total", "0", "-cover_shrink_stages", "0",
           "-cell_size", str(h), "-chain_hdpe_delta_top", str(delta),
           "-chain_hdpe_delta_bottom", "40", "-max_steps", "8000", "-output_dir", str(d), "-quiet"]
    if cohesion is not None:
        cmd += ["-mat_soil_cohesion", str(cohesion)]
    p = subprocess.run(cmd, env=MPI_ENV, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True)
    if p.returncode != 0:
        print(p.stdout[-1500:])
        sys.exit(f"pmpm failed at delta = {delta}")
    with open(d / "stages.csv") as f:
        row = list(csv.DictReader(f))[0]
    with open(d / "summary.json") as f:
        s = json.load(f)
    slip = float(row["max_slip"])
    ok = row["converged"] == "1" and slip < SLIP_LIMIT
    print(f"  delta {delta:6.3f} deg: {'holds ' if ok else 'slides'} (slip {slip:.4f} m, "
          f"{row['steps']} steps, ratio {float(row['ratio']):.2e})", flush=True)
    return ok, s


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--h", type=float, default=0.5)
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--cohesion", type=float, default=None,
                    help="cover soil cohesion (Pa) in place of the example's 2 kPa")
    a = ap.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    beta, L, phi, gamma = 18.435, 30.0, 32.0, 18e3
    h_normal = 0.6 * math.cos(math.radians(beta))
    ks = lambda d: cf.koerner_soong_fs(gamma, h_normal, L, beta, phi, d)  # noqa: E731
    lo, hi = 1.0, beta + 2  # Koerner-Soong FS = 1 between these
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if ks(mid) >= 1 else (mid, hi)
    delta_ks = hi
    print(f"closed forms: infinite slope slides below delta = beta = {beta:.2f} deg; "
          f"Koerner-Soong FS = 1 at delta = {delta_ks:.2f} deg (h = {h_normal:.3f} m normal, "
          f"L = {L} m, phi = {phi} deg)")
    rows = []
    if a.quick:
        for d in (delta_ks - 4, beta + 2):
            ok, _ = holds(d, a.h, a.np, a.cohesion)
            rows.append((d, ok))
        thr = float("nan")
    else:
        lo, hi = delta_ks - 6, beta + 3  # expected: slides at lo, holds at hi
        ok_lo, _ = holds(lo, a.h, a.np, a.cohesion)
        ok_hi, _ = holds(hi, a.h, a.np, a.cohesion)
        rows += [(lo, ok_lo), (hi, ok_hi)]
        if ok_lo or not ok_hi:
            thr = float("nan")
            print("  the threshold is outside the bracket")
        else:
            while hi - lo > 0.25:
                mid = 0.5 * (lo + hi)
                ok, _ = holds(mid, a.h, a.np, a.cohesion)
                rows.append((mid, ok))
                lo, hi = (lo, mid) if ok else (mid, hi)
            thr = 0.5 * (lo + hi)
    c_text = "c 2 kPa" if a.cohesion is None else f"c {a.cohesion / 1e3:g} kPa"
    md = [MARK_BEGIN, "## Veneer on the slope example (bench/cover_veneer.py)", "",
          f"options/cover_slope.opts, stage 0 only, h = {a.h} m, {a.np} ranks; the cover "
          f"(0.6 m vertical, {h_normal:.3f} m normal, phi {phi} deg, {c_text}) on the sheet, "
          f"slope {beta} deg over {L} m with a toe on level ground. Holds: stage 0 converges "
          f"with the slip on the sheet below {SLIP_LIMIT * 100:.0f} cm.", "",
          "| delta (deg) | pmpm |", "|---|---|"]
    md += [f"| {d:.3f} | {'holds' if ok else 'slides'} |" for d, ok in sorted(rows)]
    md += ["", f"- infinite slope: slides below delta = {beta:.2f} deg (FS = tan delta / tan beta)",
           f"- Koerner-Soong (docs/method.md, section 6.3, cohesion and adhesion zero): FS = 1 at delta = "
           f"{delta_ks:.2f} deg",
           f"- pmpm: threshold {thr:.2f} deg" + ("" if math.isnan(thr) else
                                                  f" ({thr - delta_ks:+.2f} deg from Koerner-Soong,"
                                                  f" {thr - beta:+.2f} deg from the infinite slope)"),
           "", MARK_END]
    text = "\n".join(md)
    publish(text, OUT / "VENEER.md", MARK_BEGIN, MARK_END, not a.quick and a.cohesion is None)


if __name__ == "__main__":
    main()
