#!/usr/bin/env bash
# The main job: install and build if needed, then run the landfill cover of the seed paper under
# load II and load I on 2 ranks, and plot the membrane's deflection, strain and stress (both loads
# on one plot) and the deformed shape; then a field cover with a sinkhole opening under it in
# stages (options/cover_sinkhole.opts), with its design answers and plots. Results:
# output/landfill/, output/landfill_load1/, output/cover_sinkhole/.
#
# With arguments, runs one scene instead: scripts/run.sh OPTIONS_FILE [pmpm options...]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
NP=${PMPM_RANKS:-2}
run() { mpiexec -n "$NP" --oversubscribe build/pmpm "$@"; }

if (($#)); then
  opts=$1
  shift
  # exit 3 (NOT CONVERGED) and 4 (INCONCLUSIVE) wrote their outputs: plot them, then exit with it
  rc=0
  run -options_file "$opts" "$@" || rc=$?
  if ((rc != 0 && rc != 3 && rc != 4)); then exit "$rc"; fi
  # a scene with membrane chains: plot each chain's strain, tension, slip, pressure and shape
  out=$(/usr/bin/python3 -c 'import sys; a = sys.argv[1:]; print(a[a.index("-output_dir") + 1] if "-output_dir" in a else "")' "$@")
  [ -n "$out" ] || out=output/$(sed -n 's/^-scene *//p' "$opts" | head -1)
  if compgen -G "$out/chain_*.csv" > /dev/null; then /usr/bin/python3 scripts/plot_chain.py "$out"; fi
  # a staged cover: the stage history and the deformed cover coloured by plastic strain
  if [ -f "$out/stages.csv" ]; then /usr/bin/python3 scripts/plot_cover.py "$out"; fi
  # a 3D sheet (-dim 3): its major principal strain in plan and sections through its centre
  if [ -f "$out/sheets.h5" ]; then /usr/bin/python3 scripts/plot_sheet.py "$out"; fi
  # the trapdoor: its ground reaction curve and deformed shape
  if [ -f "$out/trapdoor.csv" ]; then /usr/bin/python3 scripts/plot_trapdoor.py "$out"; fi
  exit "$rc"
fi
run -options_file options/landfill.opts -output_dir output/landfill
run -options_file options/landfill_load1.opts -output_dir output/landfill_load1
/usr/bin/python3 scripts/plot_landfill.py output/landfill --compare output/landfill_load1 \
  --labels "load II" "load I"
/usr/bin/python3 scripts/plot_landfill.py output/landfill_load1
/usr/bin/python3 - <<'PY'
import json
for name in ("landfill", "landfill_load1"):
    r = json.load(open(f"output/{name}/summary.json"))["results"]
    print(f"{name:15s} settlement at X = 15 mm {r['settlement_centre']*1e3:.3f} mm, "
          f"differential {r['differential_settlement']*1e3:.3f} mm, "
          f"peak membrane strain {r['peak_axial_strain']*100:.2f} % at X = {r['peak_axial_strain_x']*1e3:.1f} mm")
print("plots: output/landfill/*.png (ParaView: output/landfill/particles.xmf)")
PY
run -options_file options/cover_sinkhole.opts -output_dir output/cover_sinkhole
/usr/bin/python3 scripts/plot_chain.py output/cover_sinkhole
/usr/bin/python3 scripts/plot_cover.py output/cover_sinkhole
echo "cover_sinkhole: output/cover_sinkhole/stages.csv, *.png (ParaView: series/particles_series.xmf)"
