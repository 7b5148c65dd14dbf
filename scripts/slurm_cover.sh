#!/usr/bin/env bash
# A pmpm cover on a Slurm cluster (docs/cluster.md): the sinkhole example widened to
# a 100 m cover at 2 cm cells (11.2 M particles), 256 ranks on a 64 x 4 process grid, output on
# scratch, a checkpoint every CKPT_EVERY steps and at every stage's end. Submit it again after a
# time limit: it resumes from the newest complete checkpoint in the output directory.
#
#   sbatch scripts/slurm_cover.sh                 # first run, or resume
#   OPTS=options/cover_slope.opts EXTRA="-cell_size 0.05" sbatch scripts/slurm_cover.sh
#
#SBATCH --job-name=pmpm-cover
#SBATCH --nodes=4
#SBATCH --ntasks-per-node=64
#SBATCH --cpus-per-task=1
#SBATCH --time=24:00:00
#SBATCH --output=pmpm-cover-%j.out
##SBATCH --account=PROJECT          # placeholder: your allocation
##SBATCH --partition=PARTITION      # placeholder: your site's queue
set -euo pipefail

# Placeholders: the site's modules for the compiler, MPI, PETSc (with HDF5) and Eigen that pmpm
# was built with (docs/user-guide.md, "Dependencies").
# module load gcc/12 openmpi/4.1 petsc/3.18 hdf5/1.12 eigen/3.4

PMPM=${PMPM:-$HOME/pmpm/build/pmpm}
OPTS=${OPTS:-$HOME/pmpm/options/cover_sinkhole.opts}
# The 100 m cover: 2 cm cells, the void under its middle, and a step cap per stage for 2 cm
# cells (a wave crosses the model in height / (cfl h) steps: 12.5x more than at 0.25 m).
# Each option overrides the file's.
EXTRA=${EXTRA:--cell_size 0.02 -cover_width 100 -cover_void_x 50 -max_steps 500000}
# Process grid: many columns, few rows for a wide, shallow model (fewest halo bytes per rank,
# and fewer rank boundaries through the settling waste); the product must be the rank count.
GRID=${GRID:--da_processors_x 64 -da_processors_y 4}
OUT=${OUT:-${SCRATCH:-/scratch/$USER}/pmpm/cover100}
CKPT_EVERY=${CKPT_EVERY:-100000}  # steps between checkpoints (docs/cluster.md: 30-60 min of run time)

mkdir -p "$OUT"

# The newest complete checkpoint (a checkpoint in writing is checkpoint_<step>.h5.tmp, which
# this pattern skips): resume from it when there is one.
latest=""
best=-1
for f in "$OUT"/checkpoint_*.h5; do
  [ -e "$f" ] || continue
  n=${f##*/checkpoint_}
  n=${n%.h5}
  [[ $n =~ ^[0-9]+$ ]] || continue
  if ((10#$n > best)); then
    best=$((10#$n))
    latest=$f
  fi
done
RESTART=()
if [ -n "$latest" ]; then
  echo "resuming from $latest"
  RESTART=(-restart "$latest")
fi

# shellcheck disable=SC2086  # EXTRA and GRID are option lists
srun --cpu-bind=cores "$PMPM" -options_file "$OPTS" $EXTRA $GRID -balance setup \
  -output_dir "$OUT" -checkpoint_every "$CKPT_EVERY" -checkpoint_at_stage_end \
  "${RESTART[@]}" -log_view ":$OUT/log_view_${SLURM_JOB_ID:-local}.txt"
# With mpirun instead of srun: mpirun -n "$SLURM_NTASKS" --bind-to core "$PMPM" ...

# Every checkpoint is kept (about 208 bytes per particle each); delete the older ones by hand.
