"""The 3D sheet on the grid (options/sheet.opts, -scene sheet -dim 3; docs/method.md, section 10):
a circular membrane of radius a = 10 m clamped at its rim, under its own weight q = 100 Pa,
E t = 1e5 N/m, nu = 0.3, against the membrane of revolution with the same law (membrane_bvp.py)
and Foppl-Hencky's small-slope centre deflection 0.653 a (q a / E t)^(1/3).

usage: test_sheet.py EXE NP OUTDIR

Asserted at h = 1 m (331 points) and, on one rank, 0.5 m (1,261 points): the run converges
(-tol 1e-3; 6,421 and 5,673 steps); the sag within 2e-3 of the BVP (measured -8.5e-5 and
+1.5e-5) and within 2 % of Foppl-Hencky (+0.7 %: the slopes reach 0.3); the centre strain (the
mean over the centre's triangles, first order in the lattice gap) and the rim's radial strain
within 2 % (measured -0.93 % and -0.12 % at 1 m, -0.25 % and -0.03 % at 0.5 m), the centre
strain's error falling from 1 to 0.5 m; nothing wrinkles (every triangle taut: both principal
tensions are tensile over a clamped disc). The design answer's form (sheet_peak_principal): the
largest major principal strain of a point sits on the rim and equals the BVP's rim radial strain
within 1 % (measured +0.57 % and +0.34 %), the minor (hoop) strain there under 10 % of it (exact:
0; measured 7.6 % and 4.0 %, the point's triangles reach in one gap) and falling with h; a single
triangle's largest strain is no smaller (the lattice's scatter, +4.4 % and +2.3 %).
The outputs: sheets.h5 holds the lattice (points, triangles) whose displacements give the sag,
whose triangle strains give the centre strain of summary.json to 1e-12, and whose point strains
give the peak; sheets.xmf names those datasets with their shapes; sheet_membrane.csv has a row
per point; scripts/plot_sheet.py draws its two PNGs from them. On 2 ranks (the sheet crosses x = 0) and 4 ranks (2 x 2 x 1: it crosses x = 0 and
z = the centre) the h = 1 m answers equal the one-rank run's to 1e-8 (measured 5e-14; the points
are shared by an allreduce, the nodal sums' order changes). On 2: checkpoints every 2,000 steps
leave sheets.h5 bit for bit, and a restart from step 2,000 ends at the same step, bit for bit on
1 rank and within 1e-10 of the radius on 2, and so does an elastoplastic sheet's on 1 rank (its
plastic state is checkpointed). On 1 rank the elastoplastic law (plane-stress von Mises on the
forces): never yielding it is the linear sheet (1e-12; measured 3.5e-14); yielding (sigma_y t =
1,500 N/m, H t = 1e4 N/m) it converges, sags more (1.60 against 1.42 m), and every triangle lies
within its hardened yield surface (1e-9; measured 4.6e-16). On 2 and 4 ranks each rank computes
only the triangles near its cells (src/step/sheets.cpp): the yielding sheet at h = 0.5 m on a grid
cut in y (1 x 2 x 1, 1 x 2 x 2), whose sag crosses the cut so that triangles change ranks and take
their plastic state from another (asserted to happen), equals one rank's to 1e-10 (measured
4e-16 in positions, 8e-13 in plastic strains); on 2 ranks a checkpoint at step 3,000 (which takes
the triangles whole) and a restart from it end on the uninterrupted run to 1e-10 (measured 0).
"""
import subprocess
import sys
from pathlib import Path
from xml.etree import ElementTree

import h5py
import numpy as np

from membrane_bvp import membrane_bvp
from pmpmtest import Checks, run, summary

def rel(c, what, got, want, tol):
    """got within tol (absolute) of want; prints the relative difference."""
    c.check(what, abs(got - want) <= tol, f"({got:.7g} vs {want:.7g}, {got / want - 1:+.2e})")


exe, np_, out = sys.argv[1], int(sys.argv[2]), Path(sys.argv[3])
c = Checks(f"sheet_np{np_}")
A, Q, NU, ET = 10.0, 100.0, 0.3, 1e5
J = ET / (1 - NU * NU)
ex = membrane_bvp(A, Q, J, NU)
fh = 0.653 * A * (Q * A / ET)**(1 / 3)
print(f"     membrane of revolution: sag {ex['sag']:.5f} m, centre strain {ex['strain_centre']:.6f},"
      f" rim strain {ex['strain_rim']:.6f}; Foppl-Hencky {fh:.5f} m")

def check_files(c, h, o, r):
    """sheets.h5, sheets.xmf and sheet_membrane.csv against summary.json's answers."""
    with h5py.File(o / "sheets.h5", "r") as f:
        g = f["sheets/membrane"]
        x, x0, u = np.array(g["position"]), np.array(g["position0"]), np.array(g["displacement"])
        tri = np.array(g["triangles"])
        e1, e2 = np.array(g["triangle_strain_major"]), np.array(g["triangle_strain_minor"])
        pe1, pe2 = np.array(g["strain_major"]), np.array(g["strain_minor"])
        shapes = {k: g[k].shape for k in g}
    c.check(f"h = {h}: sheets.h5 has the lattice", x.shape == (r["points"], 3) and
            tri.shape == (r["triangles"], 3) and tri.min() == 0 and tri.max() == r["points"] - 1)
    c.check(f"h = {h}: displacement = position - position0", np.abs(u - (x - x0)).max() < 1e-12)
    c.check(f"h = {h}: the centre point's settlement is the sag", abs(-u[0, 1] - r["sag"]) < 1e-12)
    at0 = (tri == 0).any(axis=1)
    rel(c, f"h = {h}: centre strain from the triangles", 0.5 * (e1[at0] + e2[at0]).mean(),
        r["strain_centre"], 1e-12 * r["strain_centre"])
    k = int(np.argmax(pe1))
    c.check(f"h = {h}: the peak from the point strains", pe1[k] == r["peak_strain_major"] and
            pe2[k] == r["peak_strain_minor"] and np.abs(x[k] - r["peak_at"]).max() == 0)
    c.check(f"h = {h}: a triangle's largest strain", e1.max() == r["peak_strain_triangle"])
    bad = []
    for item in ElementTree.parse(o / "sheets.xmf").iter("DataItem"):
        path = item.text.split(":", 1)[1].split("/")[-1]
        dims = tuple(int(d) for d in item.get("Dimensions").split())
        if shapes.get(path) != dims:
            bad.append(f"{path} {dims} vs {shapes.get(path)}")
    c.check(f"h = {h}: sheets.xmf names the datasets with their shapes", not bad, "; ".join(bad))
    rows = np.loadtxt(o / "sheet_membrane.csv", delimiter=",", skiprows=1)
    c.check(f"h = {h}: sheet_membrane.csv, a row per point", rows.shape == (r["points"], 14) and
            np.abs(rows[:, 9] - pe1).max() < 1e-12 * abs(pe1).max())
    # the plots (scripts/plot_sheet.py) from these files
    p = subprocess.run([sys.executable, "scripts/plot_sheet.py", str(o)], capture_output=True,
                       text=True)
    pngs = [o / f"sheet_membrane_{k}.png" for k in ("plan", "section")]
    c.check(f"h = {h}: plot_sheet.py draws the plan and the sections", p.returncode == 0 and
            all(f.exists() and f.stat().st_size > 10000 for f in pngs), p.stderr[-300:])


meshes = [1.0, 0.5] if np_ == 1 else [1.0]
res = {}
for h in meshes:
    o = out / f"h{h}"
    run(exe, np_, ["-options_file", "options/sheet.opts", "-cell_size", str(h)], o)
    s = summary(o)
    r = s["results"]
    res[h] = r
    c.check(f"h = {h}: converged", s["converged"], f"({s['steps']} steps)")
    rel(c, f"h = {h}: sag against the BVP", r["sag"], ex["sag"], 2e-3 * ex["sag"])
    rel(c, f"h = {h}: sag against Foppl-Hencky", r["sag"], fh, 0.02 * fh)
    rel(c, f"h = {h}: centre strain", r["strain_centre"], ex["strain_centre"], 0.02 * ex["strain_centre"])
    rel(c, f"h = {h}: rim strain", r["strain_rim"], ex["strain_rim"], 0.02 * ex["strain_rim"])
    c.check(f"h = {h}: every triangle taut", r["triangles_not_taut"] == 0)
    rel(c, f"h = {h}: peak principal strain against the BVP's rim strain", r["peak_strain_major"],
        ex["strain_rim"], 0.01 * ex["strain_rim"])
    pk = r["peak_at"]
    c.check(f"h = {h}: the peak on the rim", abs(np.hypot(pk[0], pk[2] - A - 2 * h) - A) < 1e-9 * A,
            f"(at {pk})")
    c.check(f"h = {h}: minor strain at the peak under 10 % of the major",
            0 <= r["peak_strain_minor"] < 0.1 * r["peak_strain_major"],
            f"({r['peak_strain_minor'] / r['peak_strain_major']:.3f})")
    c.check(f"h = {h}: a triangle's largest strain no smaller",
            r["peak_strain_triangle"] >= r["peak_strain_major"])
    if np_ == 1:
        check_files(c, h, o, r)
if np_ == 1:
    # the elastoplastic law (plane-stress von Mises on the forces, linear hardening): with a yield
    # force never reached it is the linear law; with sigma_y t = 1500 N/m (below the elastic
    # sheet's 1,650 N/m at the rim) and H t = 1e4 N/m the sheet yields and sags more, and every
    # triangle stays on or inside its hardened yield surface
    plastic = ["-options_file", "options/sheet.opts", "-mat_membrane_law", "elastoplastic",
               "-mat_membrane_hardening", "1e6"]
    o = out / "plastic_elastic"
    run(exe, 1, plastic + ["-mat_membrane_yield_stress", "1e9"], o)
    rp = summary(o)["results"]
    for k in ("sag", "strain_centre", "strain_rim"):
        rel(c, f"elastoplastic, never yielding: {k} as linear", rp[k], res[1.0][k],
            1e-12 * abs(res[1.0][k]))
    o = out / "plastic"
    run(exe, 1, plastic + ["-mat_membrane_yield_stress", "1.5e5"], o)
    s = summary(o)
    rp = s["results"]
    c.check("elastoplastic, yielding: converged", s["converged"], f"({s['steps']} steps)")
    c.check("elastoplastic, yielding: sags more than the elastic sheet",
            rp["sag"] > 1.05 * res[1.0]["sag"], f"({rp['sag']:.4f} vs {res[1.0]['sag']:.4f} m)")
    with h5py.File(o / "sheets.h5", "r") as f:
        g = f["sheets/membrane"]
        n1, n2 = np.array(g["triangle_tension_major"]), np.array(g["triangle_tension_minor"])
        a = np.array(g["triangle_plastic_strain"])
    q = np.sqrt(n1 * n1 - n1 * n2 + n2 * n2)
    c.check("elastoplastic, yielding: some triangles yielded", (a > 0).sum() > 10,
            f"({(a > 0).sum()} of {len(a)})")
    over = (q - (1500 + 1e4 * a)).max() / 1500
    c.check("elastoplastic, yielding: every triangle within its yield surface (1e-9)",
            over <= 1e-9, f"(max excess {over:.2e} of the yield force)")
if len(res) > 1:
    e = [abs(res[h]["strain_centre"] / ex["strain_centre"] - 1) for h in meshes]
    c.check("centre strain's error falls from 1 to 0.5 m", e[1] < e[0], f"({e[0]:.2e} -> {e[1]:.2e})")
    m = [res[h]["peak_strain_minor"] for h in meshes]
    c.check("minor strain at the peak falls from 1 to 0.5 m", m[1] < m[0], f"({m[0]:.2e} -> {m[1]:.2e})")
def sheet_arrays(o):
    with h5py.File(o / "sheets.h5", "r") as f:
        return {k: np.array(v) for k, v in f["sheets/membrane"].items()}


if np_ > 1:
    o = out / "np1"
    run(exe, 1, ["-options_file", "options/sheet.opts"], o)
    r1 = summary(o)["results"]
    for k in ("sag", "strain_centre", "strain_rim", "peak_strain_major"):
        rel(c, f"{k}: {np_} ranks against 1", res[1.0][k], r1[k], 1e-8 * abs(r1[k]))
    # an elastoplastic sheet at h = 0.5 m whose sag (3 cells) crosses the ranks' boundary in y
    # (the grid split 1 x 2 x 1, on 4 ranks 1 x 2 x 2): a rank computes only the triangles at the
    # points whose blocks reach its nodes, and a triangle that comes to a rank takes its plastic
    # state from one that computed it (src/step/sheets.cpp; skipping that moved the sag by
    # 4e-4 of it at h = 1 m with a narrower set)
    plastic = ["-options_file", "options/sheet.opts", "-mat_membrane_law", "elastoplastic",
               "-mat_membrane_hardening", "1e6", "-mat_membrane_yield_stress", "1.5e5"]
    split = ["-cell_size", "0.5", "-da_processors_x", "1", "-da_processors_y", "2",
             "-da_processors_z", str(np_ // 2)]
    run(exe, 1, plastic + ["-cell_size", "0.5"], out / "plastic_h05")
    _, log = run(exe, np_, plastic + split + ["-info", ":sys"], out / "plastic_split")
    shared = sum(l.startswith("[0]") and "plastic state shared" in l for l in log.splitlines())
    c.check(f"elastoplastic, split in y on {np_} ranks: triangles changed ranks (state shared)",
            shared > 0, f"({shared} times)")
    pa, ps = sheet_arrays(out / "plastic_h05"), sheet_arrays(out / "plastic_split")
    for k in ("position", "triangle_plastic_strain", "triangle_tension_major"):
        d, scale = np.abs(ps[k] - pa[k]).max(), np.abs(pa[k]).max()
        c.check(f"elastoplastic, split in y on {np_} ranks: {k} within 1e-10 of 1 rank's",
                d <= 1e-10 * scale, f"({d / scale:.1e})")
if np_ == 2:
    # checkpoints (every 2,000 of the 6,421 steps) change nothing; a restart from step 2,000
    # ends bit for bit on 1 rank and within the ranks' round-off on 2
    base = sheet_arrays(out / "np1")
    ck = out / "checkpointed"
    run(exe, 1, ["-options_file", "options/sheet.opts", "-checkpoint_every", "2000"], ck)
    c.check("checkpoints written at steps 2,000, 4,000 and 6,000",
            sorted(p.name for p in ck.glob("checkpoint_*")) ==
            ["checkpoint_2000.h5", "checkpoint_4000.h5", "checkpoint_6000.h5"])
    same = lambda o: all(np.array_equal(base[k], v) for k, v in sheet_arrays(o).items())
    c.check("writing checkpoints: sheets.h5 bit for bit", same(ck))
    for n in (1, 2):
        o = out / f"restart_np{n}"
        run(exe, n, ["-options_file", "options/sheet.opts", "-restart",
                     str(ck / "checkpoint_2000.h5")], o)
        s2 = summary(o)
        c.check(f"restart on {n} rank(s): converged at the same step", s2["steps"] ==
                summary(out / "np1")["steps"], f"({s2['steps']})")
        if n == 1:
            c.check("restart on 1 rank: sheets.h5 bit for bit", same(o))
        else:
            d = np.abs(sheet_arrays(o)["position"] - base["position"]).max()
            c.check("restart on 2 ranks: sheet positions within 1e-10 of the radius", d <= 1e-10 * A,
                    f"({d:.2e} m)")
    # the elastoplastic sheet's plastic state is checkpointed: a restart ends bit for bit
    plastic = ["-options_file", "options/sheet.opts", "-mat_membrane_law", "elastoplastic",
               "-mat_membrane_hardening", "1e6", "-mat_membrane_yield_stress", "1.5e5"]
    run(exe, 1, plastic, out / "plastic")
    run(exe, 1, plastic + ["-checkpoint_every", "3000"], out / "plastic_ck")
    run(exe, 1, plastic + ["-restart", str(out / "plastic_ck" / "checkpoint_3000.h5")],
        out / "plastic_restart")
    pa, pr = sheet_arrays(out / "plastic"), sheet_arrays(out / "plastic_restart")
    c.check("elastoplastic: a restart from step 3,000 ends bit for bit (plastic strains too)",
            all(np.array_equal(pa[k], v) for k, v in pr.items()))
    # on 2 ranks (each computes its half of the triangles), a checkpoint between steps (which
    # takes them whole) and a restart from it end where the uninterrupted run ends
    run(exe, 2, plastic, out / "plastic_np2")
    run(exe, 2, plastic + ["-checkpoint_every", "3000"], out / "plastic_np2_ck")
    run(exe, 2, plastic + ["-restart", str(out / "plastic_np2_ck" / "checkpoint_3000.h5")],
        out / "plastic_np2_restart")
    p2, pr = sheet_arrays(out / "plastic_np2"), sheet_arrays(out / "plastic_np2_restart")
    for k in ("position", "triangle_plastic_strain"):
        d, scale = np.abs(pr[k] - p2[k]).max(), np.abs(p2[k]).max()
        c.check(f"elastoplastic on 2 ranks: a restart from step 3,000, {k} within 1e-10",
                d <= 1e-10 * scale, f"({d / scale:.1e})")
c.done()
