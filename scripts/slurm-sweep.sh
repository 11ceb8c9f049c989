#!/usr/bin/env bash
# A Slurm job array for a flocking sweep: task i of N runs shard i/N of the sweep into OUT/shard-i;
# once every task has finished, join the shards:
#
#     sbatch --array=0-99 scripts/slurm-sweep.sh sweeps/alg2_c1_n.ron out/alg2-slurm
#     flocking sweep merge --out out/alg2-slurm/merged out/alg2-slurm/shard-*
#
# OUT is the shards' own directory: not the --out of a `flocking sweep` (it would mix the two).
#
# (or chain the merge: `sbatch --dependency=afterok:<array job id> --wrap "flocking sweep merge …"`).
# Each task runs its runs one at a time on one core (--jobs 1, --cpus-per-task 1); a task that is
# killed or preempted resumes when resubmitted (finished runs are kept in OUT/shard-i/rows).
# FLOCKING is the flocking binary to use (default: flocking on the PATH).
#SBATCH --job-name=flock-sweep
#SBATCH --cpus-per-task=1
#SBATCH --output=flock-sweep-%A_%a.out
set -euo pipefail

sweep=${1:?usage: sbatch --array=0-(N-1) scripts/slurm-sweep.sh SWEEP.ron OUT}
out=${2:?usage: sbatch --array=0-(N-1) scripts/slurm-sweep.sh SWEEP.ron OUT}
cli=${FLOCKING:-flocking}
task=${SLURM_ARRAY_TASK_ID:?not in a Slurm job array (submit with sbatch --array=0-(N-1))}
count=${SLURM_ARRAY_TASK_COUNT:?not in a Slurm job array}

exec "$cli" sweep "$sweep" --out "$out/shard-$task" --shard "$task/$count" --jobs 1 --quiet
