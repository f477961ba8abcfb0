#!/usr/bin/env bash
# One shard of a grassbench sweep as a Slurm array task:
#
#   sbatch --array=0-15 experiments/slurm/job.sh experiments/compare_all.toml results/compare_all
#   # once every task is done:
#   grassbench merge results/compare_all-* -o results/compare_all && grassbench report results/compare_all
#
# Task I of N runs every N-th comparison group from I (a scene variant, size, MSAA and
# repetition with all its techniques and its reference), into OUT-I. Slurm sets
# SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT; anything else that sets them (GNU parallel,
# a shell loop: the test suite does) runs the same shard. GRASSBENCH names the binary
# (default: `grassbench` on the PATH).
#SBATCH --job-name=grassbench
#SBATCH --output=grassbench-%A_%a.log
set -euo pipefail
sweep=${1:?usage: job.sh SWEEP.toml OUT_PREFIX [grassbench sweep options...]}
out=${2:?usage: job.sh SWEEP.toml OUT_PREFIX [grassbench sweep options...]}
shift 2
task=${SLURM_ARRAY_TASK_ID:?SLURM_ARRAY_TASK_ID is not set: run under sbatch --array, or set it}
count=${SLURM_ARRAY_TASK_COUNT:?SLURM_ARRAY_TASK_COUNT is not set: run under sbatch --array, or set it}
exec "${GRASSBENCH:-grassbench}" sweep "$sweep" --shard "$task/$count" -o "$out-$task" "$@"
