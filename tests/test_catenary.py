"""The elastic catenary (docs/method.md, section 6.1): one membrane chain alone, pinned at both ends.

usage: test_catenary.py EXE NP OUTDIR [pmpm options for every run]
Checked against the closed form computed here, independently of the scene (closed_forms.py):
sag, mid-span and support strain, mid-span tension within 1 % (the issue's bound), for
  - the check case of docs/method.md, section 6.1 (l = L0 = 10 m, w = 100 N/m^2, J = 1e5 N/m, strain 1.6 %) at
    h = 0.5 and 0.25 m (20 and 40 cells over the span), one chain point per cell and the
    projected strain as the options file and the defaults ship them, within 1 % (measured values:
    docs/verification.md); at h = 1 m (10 cells) the mid-span strain within 1.5 %: its error falls
    as h^2; catenary_chord_np1 repeats the test with the chord strain (-chain_strain_projection
    0) and catenary_projection_np1 with four points per cell (-chain_spacing 0.25), where the
    chord strain is 0.95 % off at h = 1 m and the projected one 1.7e-4;
  - a soft sheet past 5 % strain (J = 1e4 N/m: 7.0 % mid-span, 8.6 % at the supports);
  - grid independence (one rank): the three meshes agree within 1 % in sag and peak strain (the
    peak is the end segment's strain, so at h = 1 m it averages the strain's rise toward the
    support over a cell), and moving the chain by (0.34, 0.62) of a cell changes the peak strain
    by less than 2 %;
  - two named chains in one scene, each with its own material (-mat_liner_*, twice the weight):
    each against its own closed form (measured 8.6e-4 in sag).
The support strain is extrapolated from the two end segments; the pinned points are supports
held off the grid, and the horizontal reaction equals H to 7e-4 (h = 0.5 m).
"""
import sys
import closed_forms as cf
from pmpmtest import Checks, run, summary

exe, np, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
extra_all = sys.argv[4:]
c = Checks(f"catenary_np{np}" + (" " + " ".join(extra_all) if extra_all else ""))


def case(name, *extra):
    d = f"{out}/{name}"
    run(exe, np, ["-options_file", "options/catenary.opts"] + list(extra) + extra_all, d)
    s = summary(d)
    c.check(f"{name}: converged", s["converged"] is True, f"(ratio {s['unbalanced_force_ratio']:.2e})")
    return s


def against_exact(name, s, J, bound=0.01):
    r = s["results"]
    ex = cf.catenary(r["span"], r["span"], r["weight_per_length"], J)
    c.check(f"{name}: axial stiffness J reported", abs(r["axial_stiffness"] / J - 1) < 1e-12)
    for key, want in (("sag", ex["sag"]), ("strain_mid", ex["strain_mid"]),
                      ("strain_support", ex["strain_support"]), ("tension_mid", ex["H"])):
        c.le(f"{name}: {key} relative error", abs(r[key] / want - 1), bound)
    c.le(f"{name}: horizontal reaction / H - 1", abs(r["horizontal_reaction"] / ex["H"] - 1), 0.01)
    return r


base = {}
# the refinement study runs on one rank; two ranks repeat the rest
for h in (("1", "0.5", "0.25") if np == 1 else ("0.5",)):
    s = case(f"h{h}", "-cell_size", h)
    # ten cells over the span: the mid-span strain's O(h^2) error (bound 1.5 %)
    base[h] = against_exact(f"J = 1e5, h = {h} m", s, 1e5, 0.015 if h == "1" else 0.01)
    base[h]["peak"] = s["chains"]["membrane"]["peak_strain"]
for h in (("1", "0.5") if np == 1 else ()):
    for key in ("sag", "peak"):
        c.le(f"grid independence: {key} at h = {h} against h = 0.25",
             abs(base[h][key] / base["0.25"][key] - 1), 0.01)
s = case("soft", "-mat_membrane_E", "1e6")
r = against_exact("J = 1e4 (8.6 % at the supports)", s, 1e4)
c.ge("J = 1e4: support strain is past 5 %", r["strain_support"], 0.05)
s = case("offset", "-catenary_offset", "0.17,0.31")
c.le("chain moved by (0.34, 0.62) cells: peak strain change",
     abs(s["chains"]["membrane"]["peak_strain"] / base["0.5"]["peak"] - 1), 0.02)
against_exact("offset", s, 1e5)
# two named chains, each with its own material: the membrane and a liner twice as heavy below it
s = case("two_chains", "-catenary_second", "-mat_liner_E", "1e7", "-mat_liner_nu", "0",
         "-mat_liner_axial_stiffness", "uniaxial", "-mat_liner_gamma", "2e4")
c.check("two chains: both named in the summary", sorted(s["chains"]) == ["liner", "membrane"])
r = s["results"]
against_exact("two chains, the membrane", s, 1e5)
ex = cf.catenary(r["span"], r["span"], 200.0, 1e5)
c.le("two chains, the liner (w = 200 N/m^2): sag relative error", abs(r["liner_sag"] / ex["sag"] - 1), 0.01)
c.check("two chains: the liner's own J", abs(s["chains"]["liner"]["axial_stiffness"] / 1e5 - 1) < 1e-12)
c.done()
