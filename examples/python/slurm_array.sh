#!/usr/bin/env bash
# A Slurm job array over `lsys batch --shard`: task I of N builds every
# N-th item of the manifest from I, all into one output folder on shared
# storage. Each shard appends its own lines to OUT/index.jsonl (one write
# per line, O_APPEND); a task that is killed or preempted is resubmitted
# as is and skips what is already in the index (docs/batch.md, docs/scale.md).
#
#   sbatch --array=0-99 examples/python/slurm_array.sh /shared/dataset/manifest.jsonl /shared/dataset/out
#
# Keep the array under the cluster's MaxArraySize (`scontrol show config |
# grep MaxArraySize`; 1001 by default): 100 shards of a 1,000-item
# manifest are 10 items each.
#SBATCH --job-name=lsys-batch
#SBATCH --cpus-per-task=2
#SBATCH --mem=4G
#SBATCH --time=01:00:00
#SBATCH --output=lsys-batch-%A_%a.log
#SBATCH --requeue
set -euo pipefail
manifest="${1:?usage: sbatch --array=0-N examples/python/slurm_array.sh MANIFEST OUT}"
out="${2:?usage: sbatch --array=0-N examples/python/slurm_array.sh MANIFEST OUT}"
lsys="${LSYS:-lsys}"
exec "$lsys" batch "$manifest" --out "$out" \
  --shard "${SLURM_ARRAY_TASK_ID}/${SLURM_ARRAY_TASK_COUNT}" \
  --jobs "${SLURM_CPUS_PER_TASK:-1}"
