"""A geomembrane over an open trench under a cohesionless cover (options/trench.opts): the sag and
strain beside Giroud's self-consistent solution, the difference explained by the anchorage, the
cover's pressure against Terzaghi's bracket, and convergence at three cell sizes.

usage: test_trench.py EXE NP OUTDIR

The scene (B = 2 m, D = 0.75 m, H = 1 m, J = 0.6 MN/m, textured HDPE mu = tan 30 deg on both faces,
Drucker-Prager cover phi = 32 deg, c = 0) at h = 0.25, 0.125 and 0.0625 m (8, 16 and 32 cells
across the trench), the load ramp and the step budget scaled with 1 / h (800 / 4,000, 1,600 /
8,000 and 3,200 / 16,000 steps; 9 min on 2 shared cores). Measured (2 ranks), the sheet's strain
projected on the grid (-chain_strain_projection, the default):

    h (m)                      0.25      0.125     0.0625
    chord sag (m)              0.2901    0.2797    0.2847
    strain at mid-span (%)     4.41      4.55      4.52
    mean strain over void (%)  4.58      4.48      4.33
    peak strain in span (%)    4.86      4.65      4.53   (0.47, 0.20, 0.82 m from the edge)
    tension at mid-span (kN/m) 26.5      27.3      27.1
    arc pressure T/R (kPa)     14.2      14.2      14.3   (Terzaghi: K = 1 14.1, K = Ka 17.3)
    pull-in, both sides (mm)   26        24        33
    Giroud, arc pressure       0.268 m / 4.72 %, 0.268 / 4.72, 0.269 / 4.75
    Giroud + simulated pull-in 0.295 m / 4.34 %, 0.293 / 4.37, 0.303 / 4.30

With the chord strain (-chain_strain_projection 0; the numbers in the bullets below where marked)
the peak in the span was 6.49, 5.72, 5.54 % (the cell-period oscillation at the edge), the sag
0.2891, 0.2864, 0.2891 m and the mid-span strain 4.30, 4.52, 4.52 %.

Bounds and why:
- Relaxation: the runs do not reach -tol 1e-4 (the unbalanced-force ratio plateaus at 0.05-0.15:
  the anchorage slips by small steps and the c = 0 cover creeps; docs/limitations.md).
  What is checked is that the span has settled: over the last quarter of the finest run the chord
  sag and the mid-span strain move by less than 1 % (measured 0.3 % and 0.2 %), the ratio is
  below 0.3, the sheet's free ends have not pulled out (< 1 mm; measured 0.11 mm) and the sheet
  shares no node with the trench floor: the floor's particles reach the node row half a cell above
  it and the sheet's thin block only the nodes of the cell it is in, so a gap of more than 1.5
  cells keeps them apart (measured 0.42-0.44 m, 1.7 cells at h = 0.25 m; no pressure on the
  sheet's lower face at mid-span).
- Giroud (circular arc, strain only over the void): with the simulated pressure it overestimates
  the mid-span strain (4.79 % against 4.52 %) and underestimates the sag (0.270 against 0.289 m):
  the anchorage feeds 36 mm of sheet into the span. Asserted: the sign of both differences.
  Adding the simulated pull-in to Giroud's arc (arc = (B + u_L + u_R)(1 + T / J)) recovers the
  strain over the void within 8 % and the sag within 10 % (measured 6.5 %, 4.7 % and 4.9 %, 5.8 %
  since the contact's tail-share fix of 2026-12-03, below; before it 2.4 %, 0.8 % and 4.9 %,
  6.4 %, chord 1.2-3.8 % and 1.0-6.3 %): the
  remaining sag difference is the sheet's shape, which is not a circle (the cover presses harder
  near the edges than at mid-span: 10-11 kPa over the central 0.4 m, 16-19 kPa near the edges).
- Pressure: the arc pressure T_mid / R on the two finer meshes lies inside Terzaghi's bracket
  (K = 1: 14.1 kPa, K = Ka: 17.3 kPa), with 2 % allowed below K = 1: the bracket assumes vertical
  slip planes and is an estimate, not a bound (docs/method.md, section 6.4). Measured 13.92 and
  14.31 kPa since the tail-share fix (1.5 % below K = 1 at h = 0.125 m), 14.17 and 14.30 before
  it, chord 14.3 and 14.5; at h = 0.25 m (13.1 kPa now, 14.16 before) printed, not asserted; well
  below the overburden of 19 kPa.
- The contact's tail-share fix (src/contact/chain.cpp, contact_bodies; docs/benchmarks/relaxation_steps.md)
  lets these runs settle much further within the same step budgets: unbalanced-force ratio 1e-4,
  1.4e-3 and 1.2e-2 at h = 0.25, 0.125 and 0.0625 m, against 0.05-0.15 before. Their answers now
  (2 ranks): chord sag 0.2760 / 0.2797 / 0.2846 m, mid-span strain 4.25 / 4.47 / 4.53 %, mean over
  the void 4.76 / 4.59 / 4.54 %, peak in the span 4.70 / 4.65 / 4.62 %, mid-span tension 25.5 /
  26.8 / 27.2 kN/m, pull-in 14 / 26 / 31 mm; the table above is from before it.
- Convergence: the change of the peak strain in the span between successive meshes shrinks
  (-0.20 then -0.13 points; chord -0.77 then -0.18) and the two finest agree within 5 % (measured
  2.7 %; chord 3.2 %); the chord sag and the mid-span strain agree within 2 % (1.8 % and 0.6 %;
  with the chord strain 1.0 % and 0.1 %: the sag at h = 0.0625 m, its ratio 0.14 at the step
  budget, is the least settled). A caveat from the bench-scale runs
  (twice the steps; h = 0.03125 m, 64 cells across, 64,000 steps, 16 min): the span moves on a
  little (mid-span strain 4.54 -> 4.74 %, tension 27.3 -> 28.4 kN/m, chord sag 0.291 -> 0.295 m,
  arc pressure 14.6 -> 15.4 kPa) and the peak, now at the edge itself, falls to 4.8 % (5.8 % at
  h = 0.0625 m after 32,000 steps): the peak sits where the sheet bends over the trench's 90-degree
  edge, and with the sheet on a grid line instead of at mid-cell it is 7.6 % at h = 0.0625 m (the
  span within 2 %). The span's values are the converged answer; the corner peak is not.
- Ranks: the coarse run on 1 rank and on NP ranks agree to 1e-3 (measured 3.1e-4; chord 1.9e-5). Not to
  round-off: the ghost sums differ in order (stress 2e-16 apart after step 1), and the stick-slip
  of the anchorage and the yielding cover amplify that (1e-13 in the positions at step 100, 2e-6
  at step 1,000, saturating), as any path-dependent frictional state would.
"""
import os
import sys

import numpy as np

from pmpmtest import Checks, run, summary

exe, np_, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
c = Checks(f"trench_np{np_}")
OPTS = ["-options_file", "options/trench.opts", "-trench_history_every", "200"]
LEVELS = [(0.25, 800, 4000), (0.125, 1600, 8000), (0.0625, 3200, 16000)]

res = []
for h, ramp, steps in LEVELS:
    d = os.path.join(out, f"h{h}")
    run(exe, np_, OPTS + ["-cell_size", str(h), "-ramp_steps", str(ramp), "-max_steps",
                          str(steps)], d, capped=True)
    s = summary(d)
    r = s["results"]
    r["_ratio"], r["_steps"], r["_h"], r["_dir"] = s["unbalanced_force_ratio"], s["steps"], h, d
    res.append(r)
    g, ga = r["giroud"]["simulated_pressure"], r["giroud"]["anchored_simulated_pull_in"]
    print(f"     h = {h}: chord sag {r['sag_chord']:.4f} m, strain mid "
          f"{100 * r['strain_mid']:.3f} %, mean over void {100 * r['strain_mean_span']:.3f} %, "
          f"peak {100 * r['peak_strain_span']:.3f} % at {r['peak_strain_span_from_edge']:.3f} m "
          f"from the edge, T mid "
          f"{r['tension_mid'] / 1e3:.2f} kN/m, arc pressure {r['pressure_arc'] / 1e3:.2f} kPa, "
          f"pull-in {1e3 * r['pull_in_total']:.1f} mm; Giroud {g['sag']:.4f} m / "
          f"{100 * g['strain']:.3f} %, + pull-in {ga['sag']:.4f} m / {100 * ga['strain']:.3f} %; "
          f"ratio {r['_ratio']:.3g} after {r['_steps']} steps")

# the state the checks read
for r in res:
    h = r["_h"]
    ends = [r["anchorage"][side]["end_displacement"] for side in ("left", "right")]
    c.le(f"h = {h}: the sheet's free ends stay put (pull-out < 1 mm)", max(ends), 1e-3)
    c.ge(f"h = {h}: the sheet shares no node with the trench floor (gap > 1.5 cells)",
         r["gap_to_floor"], 1.5 * h)
    c.le(f"h = {h}: unbalanced-force ratio at the step budget", r["_ratio"], 0.3)
fine = res[-1]
hist = np.genfromtxt(os.path.join(fine["_dir"], "trench_history.csv"), delimiter=",",
                     names=True)
q = len(hist) * 3 // 4
for key in ("sag", "strain_mid"):
    drift = abs(hist[key][-1] / hist[key][q] - 1)
    c.le(f"finest mesh: {key} moved over the last quarter of the run (relative)", drift, 0.01)

# Giroud beside the simulation, the anchorage's share
for r in res[1:]:
    h = r["_h"]
    g, ga = r["giroud"]["simulated_pressure"], r["giroud"]["anchored_simulated_pull_in"]
    c.check(f"h = {h}: Giroud (strain only over the void) overestimates the mid-span strain",
            g["strain"] > r["strain_mid"],
            f"({100 * g['strain']:.3f} % > {100 * r['strain_mid']:.3f} %)")
    c.check(f"h = {h}: ... and underestimates the sag (the anchorage feeds sheet into the span)",
            g["sag"] < r["sag_chord"], f"({g['sag']:.4f} < {r['sag_chord']:.4f} m)")
    c.le(f"h = {h}: Giroud + simulated pull-in: strain over the void (relative)",
         abs(ga["strain"] / r["strain_mean_span"] - 1), 0.08)
    c.le(f"h = {h}: Giroud + simulated pull-in: chord sag (relative)",
         abs(ga["sag"] / r["sag_chord"] - 1), 0.10)
    t = r["terzaghi"]
    c.check(f"h = {h}: arc pressure inside Terzaghi's bracket [K = 1, K = Ka]",
            0.98 * t["K1"] <= r["pressure_arc"] <= t["Ka"],
            f"({t['K1']:.0f} <= {r['pressure_arc']:.0f} <= {t['Ka']:.0f} Pa)")
t = res[0]["terzaghi"]
print(f"     h = 0.25: arc pressure {res[0]['pressure_arc']:.0f} Pa against the bracket "
      f"[{t['K1']:.0f}, {t['Ka']:.0f}] Pa (not asserted)")

# convergence
pk = [r["peak_strain_span"] for r in res]
c.check("peak strain in the span: the change between successive meshes shrinks",
        abs(pk[2] - pk[1]) < abs(pk[1] - pk[0]),
        f"({100 * (pk[1] - pk[0]):+.3f}, {100 * (pk[2] - pk[1]):+.3f} points)")
c.le("peak strain in the span: the two finest meshes (relative)", abs(pk[2] / pk[1] - 1), 0.05)
for key in ("sag_chord", "strain_mid"):
    c.le(f"{key}: the two finest meshes (relative)", abs(res[2][key] / res[1][key] - 1), 0.02)

# rank count: the coarse run on 1 rank
if np_ > 1:
    h, ramp, steps = LEVELS[0]
    d = os.path.join(out, "h0.25_np1")
    run(exe, 1, OPTS + ["-cell_size", str(h), "-ramp_steps", str(ramp), "-max_steps",
                        str(steps)], d, capped=True)
    r1 = summary(d)["results"]
    worst = max(abs(r1[k] - res[0][k]) / abs(res[0][k])
                for k in ("sag", "strain_mid", "peak_strain_span", "tension_edge", "pressure_arc"))
    c.le(f"1 and {np_} ranks agree (largest relative difference of the coarse run's results)",
         worst, 1e-3)
c.done()
