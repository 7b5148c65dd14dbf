"""Particles crossing the rank boundary back and forth: a free elastic block (src/scenes/block.cpp,
options/block.opts) in an empty box, undamped, no gravity, on NP ranks (2: the box splits at
x = 0.5 m, through the block's starting centre).

usage: test_block.py EXE NP OUTDIR

Translation: v(t) = v0 cos(2 pi t / T), v0 = 1.8 m/s, T = 1.0472 s, driven by a uniform body
acceleration (the scene's particle weights); 5000 steps = 1.97 periods, the centre swings 0.3 m
either side of the split and the whole block changes rank (rank 0 holds 0 to 256 particles).
Rotation: omega = 10 rad/s about the block's centre (tip speed 1.8 m/s), 5000 steps = 3.2 turns.
Bounds, each checked at every step by the scene (largest mismatch over the run):
- particle count exact, total mass to 1e-12 relative (measured 0: migration moves particles whole);
- momentum equal to the initial momentum plus the impulse applied, to 1e-12 relative to
  M (|v0| + omega R) (measured 8.8e-15 translation, 3.0e-16 rotation; internal forces sum to zero
  by the partition of unity and the transfers carry momentum unchanged, so what is left is
  round-off);
- on 2 ranks: migrations > 0 (measured 61 translation, 506 rotation), the centre crosses the split
  >= 3 times in translation (measured 3) and rank 0 holds none and then all of the block;
- the centre follows the rigid motion x = 0.5 + (v0 T / 2 pi) sin(2 pi t / T) to 1e-3 m
  (measured 5.4e-6 m: the force is applied at mid-step).
Angular momentum is not conserved by the PIC/FLIP transfers (-transfer apic keeps it:
test_apic.py): the rotating block lost 34 % in 3.2 turns with pure FLIP at 2 particles per cell
(7 % at 4 per cell, all of it with -pic 0.05). Bound: a loss below 50 %, a regression guard, not a
conservation check.
"""
import math
import sys
from pmpmtest import Checks, run, summary

exe, np_, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
c = Checks(f"block_np{np_}")
N = 8 * 8 * 4  # 0.25 m square block, h = 1/32, 2 x 2 particles per cell


def common(name, s):
    r = s["results"]
    c.check(f"{name}: ran all steps", s["steps"] == 5000, f"({s['steps']})")
    c.check(f"{name}: particle count kept", s["particles"] == N and r["particles_initial"] == N
            and r["count_error_max"] == 0, f"({s['particles']} of {N})")
    c.le(f"{name}: total mass, max relative change", r["mass_error_rel_max"], 1e-12)
    c.le(f"{name}: momentum - impulse, max relative mismatch", r["momentum_error_rel_max"], 1e-12)
    if np_ > 1:
        c.ge(f"{name}: migrations", s["migrations"], 1)
    print(f"     {name}: migrations {s['migrations']}, centre crossings {r['split_crossings']:.0f}, "
          f"rank 0 held {r['rank0_particles_min']:.0f}..{r['rank0_particles_max']:.0f}, "
          f"momentum mismatch {r['momentum_error_rel_max']:.2e}, angular momentum drift "
          f"{r['angular_momentum_drift_min']:.3f}")
    return r


d = f"{out}/translation"
run(exe, np_, ["-options_file", "options/block.opts"], d)
s = summary(d)
r = common("translation", s)
T, v0 = 1.0472, 1.8
x_exact = 0.5 + v0 * T / (2 * math.pi) * math.sin(2 * math.pi * s["time"] / T)
c.le("translation: centre vs rigid motion (m)", abs(r["centre_x_final"] - x_exact), 1e-3)
if np_ > 1:
    c.ge("translation: centre crossings of the rank split", r["split_crossings"], 3)
    c.check("translation: the whole block changed rank",
            r["rank0_particles_min"] == 0 and r["rank0_particles_max"] == N,
            f"(rank 0 held {r['rank0_particles_min']:.0f}..{r['rank0_particles_max']:.0f})")

d = f"{out}/rotation"
run(exe, np_, ["-options_file", "options/block.opts", "-block_velocity", "0,0", "-block_period",
               "0", "-block_omega", "10"], d)
s = summary(d)
r = common("rotation", s)
if np_ > 1:
    c.ge("rotation: migrations (particles sweep across the split)", s["migrations"], 100)
c.ge("rotation: angular momentum loss below 50 % (not conserved by PIC/FLIP)",
     r["angular_momentum_drift_min"], -0.5)
c.done()
