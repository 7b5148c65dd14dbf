#!/usr/bin/env bash
# Bit-for-bit check of a refactoring: short runs of every shipped scene (and Newton, and 2 ranks)
# with two binaries, outputs compared exactly (scripts/bitwise_compare.py).
#   bash scripts/bitwise_compare.sh BEFORE_BINARY [AFTER_BINARY (build/pmpm)] [OUTDIR] [-k NAME]
set -euo pipefail
cd "$(dirname "$0")/.."
before=$1
after=${2:-build/pmpm}
shift $(($# < 2 ? $# : 2))
exec /usr/bin/python3 scripts/bitwise_compare.py "$before" "$after" "$@"
