#!/usr/bin/env bash
# The whole test suite: install and build if needed, then every CTest test (1 and 2 ranks).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cd build
ctest --output-on-failure -j 2 "$@"
