#!/usr/bin/python3
"""Particle-grid transfers (issue 11): FLIP, FLIP with a PIC blend, PIC and APIC (-transfer apic).

    /usr/bin/python3 bench/transfers.py          # ~3 min on 2 cores; rewrites the "Transfers"
                                                 # section of docs/benchmarks/transfers.md and
                                                 # bench/work_precision_transfers.png
    /usr/bin/python3 bench/transfers.py --quick  # h = 0.05 m only, seconds; writes
                                                 # bench/out/transfers/ only

1. Work-precision on the undamped vibrating bar (options/bar_vibration.opts, 5 periods, 1 rank):
   -cell_size 0.125, 0.05, 0.025, 0.0125 m (-max_steps scaled to keep 5 periods), -shape pmpm and
   mpm, each transfer. Errors: the energy after 5 periods (mean over the last period against the
   first: what the transfer dissipates) and the period (dispersion), against the wall time.
2. The free rotating block (options/block.opts at omega = 10 rad/s, 5000 steps = 3.2 turns, 1
   rank): the angular momentum's relative drift (APIC: particles' spin included).
3. Relaxation: the column under self-weight (options/column.opts, kinetic damping, tolerance
   1e-7) at -cfl 0.5 and 0.4: steps to converge, stress error, or the failure.
"""
import argparse
import time
from pathlib import Path

from benchmarks_md import error_line, launch, publish

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "bench" / "out" / "transfers"
PNG = ROOT / "bench" / "work_precision_transfers.png"
MARK_BEGIN, MARK_END = "<!-- transfers.py begin -->", "<!-- transfers.py end -->"
TRANSFERS = [("FLIP", ["-pic", 0]), ("FLIP + 5 % PIC", ["-pic", 0.05]), ("PIC", ["-pic", 1]),
             ("APIC", ["-transfer", "apic"])]


def dirname(name):
    """A transfer's name as part of a directory name ("FLIP + 5 % PIC" -> "FLIP_5PIC")."""
    return name.replace(' ', '').replace('%', '').replace('+', '_')


def run(args, out, timeout=3600):
    """Run pmpm on 1 rank; return (summary, None) or (None, the error line)."""
    s, output = launch(ROOT / "build" / "pmpm", 1, args, out, timeout)
    return (s, None) if s is not None else (None, error_line(output))


def bar(quick):
    hs = [0.05] if quick else [0.125, 0.05, 0.025, 0.0125]
    lines = ["### Vibrating bar: energy and period against time", "",
             "`options/bar_vibration.opts` (E = 1e7 Pa, rho = 1000 kg/m^3, L = 1 m, v0 = 0.01 m/s, "
             "-cfl 0.5, 160 steps a period at h = 0.05 m), 5 periods, 1 rank. Energy: kinetic "
             "(APIC: with the affine part, 1/2 m tr(B D^-1 B^T)) + elastic, mean over the last "
             "period / mean over the first. Period error: from the zero crossings of the "
             "centre-of-mass velocity against 2 pi / omega.", "",
             "| h (m) | shape | transfer | particles | steps | wall (s) | energy after 5 periods "
             "| period error |", "|---|---|---|---|---|---|---|---|"]
    data = []
    for h in hs:
        steps = int(round(800 * 0.05 / h))
        for shape in ("pmpm", "mpm"):
            for name, extra in TRANSFERS:
                tag = f"bar_h{h}_{shape}_{dirname(name)}"
                s, err = run(["-options_file", "options/bar_vibration.opts", "-cell_size", h,
                              "-shape", shape, "-max_steps", steps] + extra, OUT / tag)
                if s is None:
                    lines.append(f"| {h} | {shape} | {name} | | | | failed: {err[:80]} | |")
                    continue
                r = s["results"]
                e = 1 + r["energy_drift_rel"]
                lines.append(f"| {h} | {shape} | {name} | {s['particles']} | {s['steps']} | "
                             f"{s['wall_seconds']:.3f} | {e:.5f} | {r['period_error_rel']:.2e} |")
                data.append((h, shape, name, s["wall_seconds"], abs(1 - e), r["period_error_rel"]))
                print(lines[-1], flush=True)
    return lines + [""], data


def plot(data):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    marks = {"pmpm": "o-", "mpm": "s--"}
    for shape in ("pmpm", "mpm"):
        for k, (name, _) in enumerate(TRANSFERS):
            pts = sorted((t, de, dp) for h, sh, n, t, de, dp in data if sh == shape and n == name)
            if not pts:
                continue
            t = [p[0] for p in pts]
            for a, col in ((ax[0], 1), (ax[1], 2)):
                a.loglog(t, [max(p[col], 1e-12) for p in pts], marks[shape], color=f"C{k}",
                         label=f"{name}, {shape}")
    ax[0].set_ylabel("|energy after 5 periods / first period - 1|")
    ax[1].set_ylabel("period error (relative)")
    for a in ax:
        a.set_xlabel("wall time (s), 1 rank")
        a.grid(True, which="both", alpha=0.3)
    ax[0].legend(fontsize=7)
    fig.suptitle("Vibrating bar, h = 0.125 ... 0.0125 m (bench/transfers.py)")
    fig.tight_layout()
    fig.savefig(PNG, dpi=90)
    print(f"wrote {PNG}")


def block():
    lines = ["### Rotating block: angular momentum", "",
             "`options/block.opts` with `-block_velocity 0,0 -block_period 0 -block_omega 10` "
             "(-shape pmpm, 2 x 2 particles per cell, undamped), 5000 steps = 3.2 turns, 1 rank. "
             "Relative drift of the angular momentum about the centre of mass over the run "
             "(APIC: the particles' spin m (B_yx - B_xy) included). With -shape mpm every "
             "transfer stops at step 20 (a particle crossing into a nearly empty cell inverts).",
             "", "| transfer | lowest drift | highest drift | wall (s) |", "|---|---|---|---|"]
    for name, extra in TRANSFERS:
        s, err = run(["-options_file", "options/block.opts", "-block_velocity", "0,0",
                      "-block_period", "0", "-block_omega", 10] + extra,
                     OUT / f"block_{dirname(name)}")
        if s is None:
            lines.append(f"| {name} | failed: {err[:80]} | | |")
            continue
        r = s["results"]
        lines.append(f"| {name} | {r['angular_momentum_drift_min']:.3e} | "
                     f"{r['angular_momentum_drift_max']:.3e} | {s['wall_seconds']:.2f} |")
        print(lines[-1], flush=True)
    return lines + [""]


def column():
    lines = ["### Relaxation: the column under self-weight", "",
             "`options/column.opts` (kinetic damping, ramp 500 steps, tolerance 1e-7), 1 rank.",
             "", "| transfer | -cfl | steps | converged | stress error | displacement error |",
             "|---|---|---|---|---|---|"]
    for cfl in (0.5, 0.4):
        for name, extra in TRANSFERS:
            s, err = run(["-options_file", "options/column.opts", "-cfl", cfl] + extra,
                         OUT / f"column_{cfl}_{dirname(name)}")
            if s is None:
                lines.append(f"| {name} | {cfl} | | failed: {err[12:110]}... | | |")
                continue
            r = s["results"]
            lines.append(f"| {name} | {cfl} | {s['steps']} | {'yes' if s['converged'] else 'no'} "
                         f"| {r['stress_l2_error_rel']:.4e} | {r['displacement_l2_error_rel']:.4e} |")
            print(lines[-1], flush=True)
    return lines + [""]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    t0 = time.time()
    bar_lines, data = bar(a.quick)
    md = [MARK_BEGIN, "## Transfers: FLIP, PIC, APIC (bench/transfers.py)", "",
          f"`/usr/bin/python3 bench/transfers.py` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}"
          f" (this 2-core machine, shared: wall times are indicative). FLIP is `-pic 0`, FLIP + 5 % "
          "PIC the shipped default (`-pic 0.05`), PIC `-pic 1`, APIC `-transfer apic`.", ""]
    md += bar_lines
    if not a.quick:
        plot(data)
        md += ["![transfers work-precision](bench/work_precision_transfers.png)", ""]
        md += block()
        md += column()
    md += [f"({time.time() - t0:.0f} s in all.)", MARK_END]
    text = "\n".join(md) + "\n"
    publish(text, OUT / "TRANSFERS.md", MARK_BEGIN, MARK_END, not a.quick)


if __name__ == "__main__":
    main()
