#!/usr/bin/env bash
# The main job: install and build if needed, then run a scene on 2 ranks (default: the landfill
# cover under load II) and plot its results. Usage: scripts/run.sh [options-file] [pmpm options]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
opts=${1:-options/column.opts}
shift || true
mpiexec -n 2 build/pmpm -options_file "$opts" "$@"
