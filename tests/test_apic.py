"""Affine transfers (-transfer apic, include/pmpm/core/affine.hpp): the free rotating block keeps its
angular momentum to round-off; FLIP loses it. The block scene (src/scenes/block.cpp,
options/block.opts) rotating at omega = 10 rad/s about its centre, no translation, undamped, on NP
ranks (2: the split at x = 0.5 m runs through the block's centre, particles sweep across it).

usage: test_apic.py EXE NP OUTDIR

1. APIC, 5000 steps = 3.2 turns: the angular momentum about the centre of mass, particles' spin
   m_p (B_yx - B_xy) included, stays within 1e-10 relative of its start at every step (measured
   9.7e-15 on 1 rank, 5.7e-15 on 2 with 599 migrations); mass, count and momentum as in test_block.py (1e-12). The argument
   (affine.hpp) is exact algebra, so what is left is round-off accumulated over 5000 steps.
2. FLIP (-pic 0, the options file's), the same motion for 1000 steps (0.64 turn): it loses more
   than 5 % (measured 8.9 %): the test can tell the two apart. (test_block.py has the
   full 3.2 turns: -34 %.)
3. Restart: APIC writing a checkpoint at step 500 of 1000, restarted from it on the same ranks,
   ends bit for bit as the uninterrupted run (positions, velocities, stresses, F: the velocities
   depend on B, so B must come back exactly) with the same angular momentum record; on 2 ranks
   the checkpoint restarted on 1 rank agrees within 1e-10 of each field's largest value (measured
   5e-16 in position, 2e-15 in velocity, 1e-13 in stress: the ghost sums add in another order,
   and test_restart.py bounds the same by 1e-10); the checkpoint restarted with -transfer flip
   stops with an error naming -transfer.
"""
import os
import sys

import h5py
import numpy as np
from pmpmtest import Checks, particles, run, summary

exe, np_, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
c = Checks(f"apic_np{np_}")
N = 8 * 8 * 4  # 0.25 m square block, h = 1/32, 2 x 2 particles per cell
ROT = ["-options_file", "options/block.opts", "-block_velocity", "0,0", "-block_period", "0",
       "-block_omega", "10"]
APIC = ROT + ["-transfer", "apic"]
FIELDS = ("position", "velocity", "stress", "F", "id")


def conserved(name, s, steps):
    r = s["results"]
    c.check(f"{name}: ran all steps", s["steps"] == steps, f"({s['steps']})")
    c.check(f"{name}: particle count kept", s["particles"] == N and r["count_error_max"] == 0,
            f"({s['particles']} of {N})")
    c.le(f"{name}: total mass, max relative change", r["mass_error_rel_max"], 1e-12)
    c.le(f"{name}: momentum - impulse, max relative mismatch", r["momentum_error_rel_max"], 1e-12)
    return r


# 1. APIC keeps the angular momentum
d = f"{out}/apic"
run(exe, np_, APIC, d)
s = summary(d)
r = conserved("apic", s, 5000)
drift = max(abs(r["angular_momentum_drift_min"]), abs(r["angular_momentum_drift_max"]))
print(f"     apic: angular momentum {r['angular_momentum_initial']:.6g} kg m^2/s, relative drift "
      f"{r['angular_momentum_drift_min']:.3e} .. {r['angular_momentum_drift_max']:.3e}, "
      f"migrations {s['migrations']}")
c.le("apic: angular momentum, max relative drift over 3.2 turns", drift, 1e-10)
if np_ > 1:
    c.ge("apic: migrations (particles sweep across the split)", s["migrations"], 100)

# 2. FLIP loses it
d = f"{out}/flip"
run(exe, np_, ROT + ["-max_steps", "1000"], d)
s = summary(d)
r = conserved("flip", s, 1000)
print(f"     flip: relative drift {r['angular_momentum_drift_min']:.3e} after 1000 steps")
c.le("flip: angular momentum lost over 0.64 turn (relative drift)",
     r["angular_momentum_drift_min"], -0.05)

# 3. checkpoint and restart with the affine field
base, rs = f"{out}/apic_ck", f"{out}/apic_restart"
run(exe, np_, APIC + ["-max_steps", "1000", "-checkpoint_every", "500"], base)
ck = os.path.abspath(f"{base}/checkpoint_500.h5")
c.check("the APIC checkpoint holds the affine matrix",
        os.path.exists(ck) and h5py.File(ck, "r")["particles/B"].shape[0] == 4 * N)
run(exe, np_, APIC + ["-max_steps", "1000", "-restart", ck], rs)
with h5py.File(f"{base}/particles.h5", "r") as fa, h5py.File(f"{rs}/particles.h5", "r") as fb:
    same = all(np.array_equal(fa["particles/" + k][:], fb["particles/" + k][:]) for k in FIELDS)
c.check("restarted at step 500: particles bit for bit (same order)", same)
ra, rb = summary(base)["results"], summary(rs)["results"]
c.check("restarted: same angular momentum record",
        all(ra[k] == rb[k] for k in ("angular_momentum_initial", "angular_momentum_drift_min",
                                     "angular_momentum_drift_max")))
if np_ > 1:  # the 2-rank checkpoint on 1 rank: the affine field redistributed with the particles
    r1 = f"{out}/apic_restart_np1"
    run(exe, 1, APIC + ["-max_steps", "1000", "-restart", ck], r1)
    ia, pa = particles(base, ("position", "velocity", "stress"))
    ib, pb = particles(r1, ("position", "velocity", "stress"))
    c.check("restarted on 1 rank: same particles", np.array_equal(ia, ib))
    for k in pa:
        e = np.abs(pa[k] - pb[k]).max() / np.abs(pa[k]).max()
        c.le(f"restarted on 1 rank: {k}, max difference relative to its largest value", e, 1e-10)
code, text = run(exe, np_, ROT + ["-max_steps", "1000", "-restart", ck], f"{out}/wrong_transfer",
                 expect_ok=False)
lines = [ln for ln in text.splitlines() if ln.startswith("pmpm: error")]
c.check("APIC checkpoint restarted with FLIP: an error naming -transfer",
        code != 0 and len(lines) >= 1 and "-transfer" in lines[0], f"(exit {code})")
c.done()
