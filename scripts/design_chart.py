#!/usr/bin/python3
r"""The membrane-over-a-void design chart in one command: one staged pmpm run that widens the
void stage by stage, compared with Giroud's tensioned membrane and Terzaghi's arching.

Usage (Debian python, not pyenv), from anywhere:
    /usr/bin/python3 scripts/design_chart.py [--opts FILE] [--widths w1,w2,...] [--np N]
                                             [--out DIR] [--no-run] [extra pmpm options...]

Runs, with OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1,
    mpiexec -n N build/pmpm -options_file FILE [extra options] -cover_void_widths W -output_dir DIR
(defaults: FILE options/cover_sinkhole.opts, W 0.5,1,1.5,2,2.5,3, N 2, DIR output/design_chart;
relative FILE / DIR are taken from the current directory, pmpm from the repository that holds
this script). Options not recognised here (e.g. -cell_size 0.5) go to pmpm unchanged; --no-run
only re-reads an existing DIR. Then reads DIR/stages.csv and DIR/summary.json and, for each void
stage (its width B = the void's effective width in whole particle columns, stages.csv void_width),
evaluates with tests/closed_forms.py, using gamma, H, J (and phi, cohesion if present) of
summary.json results.void (they do not depend on B):
    giroud_pressure   arching_pressure_paper(gamma, B, H): Terzaghi with K tan(phi) = 0.25
    giroud_*          giroud_self_consistent(giroud_pressure, B, J): strain, sag, tension
    terzaghi_K1/Ka    terzaghi_arching(gamma, B, H, K, phi[, c]) with K = 1 and
                      K = Ka = (1 - sin phi) / (1 + sin phi) (empty without phi)

Writes into DIR:
    design_chart.csv  one row per void stage: void_width (m), pmpm_peak_strain, giroud_strain
                      (fractions), pmpm_void_pressure, giroud_pressure, terzaghi_K1,
                      terzaghi_Ka (Pa), pmpm_sag, giroud_sag (m), converged (0/1),
                      giroud_tension (N/m); an empty cell where a closed form has no answer
    design_chart.png  left: peak membrane strain (%) against void width, pmpm (markers + line;
                      open red markers: stage not converged) and Giroud, with the allowable
                      strain dashed; right: the pressure on the sheet over the void (kPa)
                      against width, pmpm, Giroud's (K tan phi = 0.25) and the Terzaghi bracket
                      between K = Ka and K = 1 shaded
and prints the table. Exits non-zero if pmpm fails or its output lacks the void results.
"""

import argparse
import csv
import json
import math
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "tests"))
import closed_forms as cf  # noqa: E402

PMPM = os.path.join(REPO, "build", "pmpm")
COLUMNS = ["void_width", "pmpm_peak_strain", "giroud_strain", "pmpm_void_pressure",
           "giroud_pressure", "terzaghi_K1", "terzaghi_Ka", "pmpm_sag", "giroud_sag",
           "converged", "giroud_tension"]


def fail(msg):
    sys.exit(f"design_chart.py: {msg}")


def parse_args(argv):
    ap = argparse.ArgumentParser(
        description="Run a staged cover void (widening) and chart the membrane's strain and "
                    "the arching pressure against the void's width, with Giroud and Terzaghi. "
                    "Unrecognised options are passed to pmpm.")
    ap.add_argument("--opts", default=os.path.join(REPO, "options", "cover_sinkhole.opts"),
                    help="pmpm options file (default: options/cover_sinkhole.opts)")
    ap.add_argument("--widths", default="0.5,1,1.5,2,2.5,3",
                    help="void widths, one stage each (m, comma-separated)")
    ap.add_argument("--np", type=int, default=2, help="MPI ranks (default 2)")
    ap.add_argument("--out", default=os.path.join(REPO, "output", "design_chart"),
                    help="output directory (default output/design_chart)")
    ap.add_argument("--no-run", action="store_true",
                    help="do not run pmpm; chart the existing output in --out")
    args, extra = ap.parse_known_args(argv)
    try:
        widths = [float(w) for w in args.widths.split(",") if w.strip()]
    except ValueError:
        fail(f"--widths {args.widths!r}: expected comma-separated numbers")
    if not widths or any(not w > 0 for w in widths):
        fail(f"--widths {args.widths!r}: expected positive widths")
    if args.np < 1:
        fail("--np must be at least 1")
    return args, extra


def run_pmpm(args, extra):
    """One staged pmpm run; its output streams to the terminal."""
    if not os.path.isfile(PMPM):
        fail(f"{PMPM} not found: build pmpm first (scripts/setup.sh)")
    if not os.path.isfile(args.opts):
        fail(f"options file {args.opts} not found")
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    # the options file first: later options on the command line override it
    cmd = (["mpiexec", "-n", str(args.np), PMPM, "-options_file", os.path.abspath(args.opts)]
           + extra + ["-cover_void_widths", args.widths, "-output_dir", args.out])
    print("running:", " ".join(cmd), flush=True)
    rc = subprocess.call(cmd, env=env)
    if rc == 3:  # the chart is drawn, but its stages are not all equilibria
        print("warning: some stages stopped at their step cap (NOT CONVERGED): the chart's "
              "points from them on are not design answers", flush=True)
    elif rc not in (0, 4):
        fail(f"pmpm exited with status {rc}")


def read_stages(path):
    if not os.path.isfile(path):
        fail(f"{path} not found: not the output of a `-scene cover` run")
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    need = {"kind", "void_width", "peak_strain", "void_pressure", "void_sag", "converged"}
    if not rows or not need <= set(rows[0]):
        fail(f"{path}: no rows or missing columns {sorted(need - set(rows[0] if rows else []))}")
    return rows


def closed_forms(void, B):
    """Giroud's self-consistent membrane and Terzaghi's bracket for a void of width B (m)."""
    gamma, H, J = float(void["gamma"]), float(void["H"]), float(void["J"])
    out = dict.fromkeys(["giroud_pressure", "giroud_strain", "giroud_sag", "giroud_tension",
                         "terzaghi_K1", "terzaghi_Ka"], None)
    p = cf.arching_pressure_paper(gamma, B, H)
    out["giroud_pressure"] = p
    try:
        g = cf.giroud_self_consistent(p, B, J)
        out.update(giroud_strain=g["eps"], giroud_sag=g["y"], giroud_tension=g["T"])
    except ValueError as e:  # the sheet cannot carry the load: no equilibrium sag
        print(f"design_chart.py: warning: B = {B:g} m: {e}", file=sys.stderr)
    phi = void.get("phi")
    if phi:
        c = float(void.get("cohesion", 0.0))  # pmpm reports it with the bracket (its c term)
        Ka = (1.0 - math.sin(math.radians(phi))) / (1.0 + math.sin(math.radians(phi)))
        out["terzaghi_K1"] = cf.terzaghi_arching(gamma, B, H, 1.0, phi, c)
        out["terzaghi_Ka"] = cf.terzaghi_arching(gamma, B, H, Ka, phi, c)
    return out


def build_table(rows, void):
    table = []
    for r in rows:
        if r["kind"] != "void":
            continue
        B = float(r["void_width"])
        row = dict(void_width=B, pmpm_peak_strain=float(r["peak_strain"]),
                   pmpm_void_pressure=float(r["void_pressure"]), pmpm_sag=float(r["void_sag"]),
                   converged=int(float(r["converged"])))
        row.update(closed_forms(void, B))
        table.append(row)
    if not table:
        fail("stages.csv has no void stage")
    return table


def fmt(v, spec):
    return "" if v is None else format(v, spec)


def write_csv(table, path):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(COLUMNS)
        for r in table:
            w.writerow([fmt(r[k], "d" if k == "converged" else ".8g") for k in COLUMNS])


def print_table(table, void, allow):
    print(f"\ncover over the void: H = {void['H']:g} m, gamma = {void['gamma']:g} N/m^3, "
          f"J = {void['J']:.4g} N/m" + (f", phi = {void['phi']:g} deg" if "phi" in void else "")
          + (f", c = {void['cohesion']:g} Pa" if "cohesion" in void else ""))
    hdr = (f"{'B (m)':>7} {'strain pmpm':>11} {'Giroud':>8} {'p pmpm':>9} {'Giroud':>9} "
           f"{'Terz K=1':>9} {'Terz Ka':>9} {'sag pmpm':>9} {'Giroud':>8} {'conv':>5}")
    print(hdr)
    print(f"{'':>7} {'(%)':>11} {'(%)':>8} {'(kPa)':>9} {'(kPa)':>9} {'(kPa)':>9} "
          f"{'(kPa)':>9} {'(m)':>9} {'(m)':>8}")

    def pc(v):
        return fmt(None if v is None else 100.0 * v, ".3f")

    def kp(v):
        return fmt(None if v is None else 1e-3 * v, ".2f")

    for r in table:
        print(f"{r['void_width']:7.3f} {pc(r['pmpm_peak_strain']):>11} "
              f"{pc(r['giroud_strain']):>8} {kp(r['pmpm_void_pressure']):>9} "
              f"{kp(r['giroud_pressure']):>9} {kp(r['terzaghi_K1']):>9} "
              f"{kp(r['terzaghi_Ka']):>9} {fmt(r['pmpm_sag'], '.4f'):>9} "
              f"{fmt(r['giroud_sag'], '.4f'):>8} {'yes' if r['converged'] else 'NO':>5}")
    if allow:
        print(f"allowable strain {100.0 * allow:g} %")


def column(table, key):
    """A column as floats, NaN where a closed form had no answer (gaps in the plot)."""
    return np.array([np.nan if r[key] is None else r[key] for r in table], float)


def plot_chart(table, void, allow, title, path):
    B = column(table, "void_width")
    conv = column(table, "converged").astype(bool)
    # closed forms on a fine grid of widths between the stages' (smooth curves)
    Bf = np.linspace(0.0, 1.05 * B.max(), 200)[1:]
    cfs = [closed_forms(void, b) for b in Bf]

    def cfcol(key):
        return np.array([np.nan if c[key] is None else c[key] for c in cfs], float)

    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12.5, 4.8))
    s = 100.0 * column(table, "pmpm_peak_strain")
    a1.plot(B, s, "-", color="tab:blue", lw=1.3)
    a1.plot(B[conv], s[conv], "o", color="tab:blue", label="pmpm (peak strain)")
    if not conv.all():
        a1.plot(B[~conv], s[~conv], "o", mfc="white", mec="tab:red",
                label="pmpm, stage not converged")
    a1.plot(Bf, 100.0 * cfcol("giroud_strain"), "-", color="k", lw=1.2,
            label="Giroud, self-consistent (K tan$\\phi$ = 0.25)")
    a1.plot(B, 100.0 * column(table, "giroud_strain"), "x", color="k", ms=6)
    if allow:
        a1.axhline(100.0 * allow, ls="--", color="tab:red", label=f"allowable {100 * allow:g} %")
    a1.set_xlabel("void width B (m)")
    a1.set_ylabel("membrane strain (%)")
    a1.set_title("membrane strain over the void")
    a1.set_xlim(0, Bf[-1])
    top = np.nanmax(np.concatenate([s, 100.0 * cfcol("giroud_strain"), [100.0 * (allow or 0)]]))
    a1.set_ylim(0, 1.12 * top)
    a1.grid(alpha=0.3)
    # legends under the panels: inside, they hide the allowable and overburden lines
    a1.legend(fontsize=9, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)

    k1, ka = 1e-3 * cfcol("terzaghi_K1"), 1e-3 * cfcol("terzaghi_Ka")
    if np.isfinite(k1).any():
        phi = void.get("phi")
        a2.fill_between(Bf, np.maximum(k1, 0), np.maximum(ka, 0), color="tab:green", alpha=0.2,
                        lw=0, label=f"Terzaghi bracket ($\\phi$ = {phi:g}$^\\circ$)")
        a2.plot(Bf, np.maximum(ka, 0), "-", color="tab:green", lw=1,
                label="Terzaghi, K = Ka")
        a2.plot(Bf, np.maximum(k1, 0), "--", color="tab:green", lw=1, label="Terzaghi, K = 1")
    a2.plot(Bf, 1e-3 * cfcol("giroud_pressure"), "-", color="k", lw=1.2,
            label="Giroud (K tan$\\phi$ = 0.25)")
    p = 1e-3 * column(table, "pmpm_void_pressure")
    a2.plot(B, p, "-", color="tab:blue", lw=1.3)
    a2.plot(B[conv], p[conv], "o", color="tab:blue", label="pmpm (mean over the void)")
    if not conv.all():
        a2.plot(B[~conv], p[~conv], "o", mfc="white", mec="tab:red",
                label="pmpm, stage not converged")
    a2.axhline(1e-3 * void["gamma"] * void["H"], ls=":", color="0.4",
               label="overburden $\\gamma$H")
    a2.set_xlabel("void width B (m)")
    a2.set_ylabel("pressure on the sheet over the void (kPa)")
    a2.set_title("arching: pressure on the sheet")
    a2.set_xlim(0, Bf[-1])
    a2.set_ylim(0, 1.12 * np.nanmax(np.concatenate([p, ka, [1e-3 * void["gamma"] * void["H"]]])))
    a2.grid(alpha=0.3)
    a2.legend(fontsize=9, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=130, bbox_inches="tight")
    plt.close(fig)


def main(argv):
    args, extra = parse_args(argv)
    args.out = os.path.abspath(args.out)
    if not args.no_run:
        run_pmpm(args, extra)
    rows = read_stages(os.path.join(args.out, "stages.csv"))
    spath = os.path.join(args.out, "summary.json")
    try:
        with open(spath) as f:
            res = json.load(f)["results"]
    except (OSError, ValueError, KeyError) as e:
        fail(f"cannot read results from {spath}: {e}")
    void = res.get("void")
    if not void or not all(k in void for k in ("gamma", "H", "J")):
        fail(f"{spath} has no results.void with gamma, H and J: no void stage in this run?")
    allow = res.get("membrane", {}).get("allowable_strain")

    table = build_table(rows, void)
    csv_path = os.path.join(args.out, "design_chart.csv")
    png_path = os.path.join(args.out, "design_chart.png")
    write_csv(table, csv_path)
    title = (f"{os.path.basename(args.opts) if not args.no_run else args.out}: cover "
             f"H = {void['H']:g} m over the sheet, $\\gamma$ = {void['gamma'] / 1e3:g} kN/m$^3$, "
             f"J = {void['J'] / 1e3:.0f} kN/m; one staged run, void widened stage by stage")
    plot_chart(table, void, allow, title, png_path)
    print_table(table, void, allow)
    if not all(r["converged"] for r in table):
        print("warning: some void stages did not converge (conv NO): their values are not at "
              "equilibrium", file=sys.stderr)
    print(f"wrote {csv_path}\nwrote {png_path}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
