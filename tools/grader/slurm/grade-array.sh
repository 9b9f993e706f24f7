#!/usr/bin/env bash
# A Slurm array that grades a batch in shards (docs/grading-reference.md, "Splitting a batch over machines"):
# task k of n grades the k-th slice of the sorted submissions into one shared BATCHDIR, whose
# per-submission folders never overlap between shards. After the array:
#   cat $(for k in $(seq 1 8); do echo "$BATCHDIR/grades-$k-of-8.csv"; done) > grades.csv
# (only shard 1 writes a header). A task that was preempted or failed is simply run again: it
# skips what it already graded.
#
#   CLOTHREF=clothref/build/bin/clothref SUBMISSIONS=submissions BATCHDIR=$SCRATCH/batch \
#     sbatch tools/grader/slurm/grade-array.sh
#
# Environment: CLOTHREF (default: clothref on PATH), SUBMISSIONS (a folder of submission folders,
# every one graded, dot folders included; default submissions), BATCHDIR (default $SCRATCH/batch), GRADE_OPTIONS (more options for every
# submission, e.g. "--timeout 10"). `sbatch --array=0-2` overrides the array below.
#SBATCH --array=0-7
#SBATCH --cpus-per-task=2
#SBATCH --job-name=clothref-grade
set -euo pipefail
k=$((SLURM_ARRAY_TASK_ID + 1))
header=""
if [ "$k" -gt 1 ]; then header=--csv-no-header; fi  # shard 1 writes the CSV header
# Every folder, those whose name starts with a dot too (a batch names them _.hidden): without
# dotglob the glob skips them and their students get no row at all.
shopt -s dotglob nullglob
submissions=("${SUBMISSIONS:-submissions}"/*/)
if [ ${#submissions[@]} -eq 0 ]; then
  echo "grade-array.sh: no submission folder in ${SUBMISSIONS:-submissions}" >&2
  exit 2
fi
# shellcheck disable=SC2086 # GRADE_OPTIONS and header are lists of words
"${CLOTHREF:-clothref}" grade "${submissions[@]}" --out "${BATCHDIR:-$SCRATCH/batch}" \
  --jobs 2 --shard "$k/$SLURM_ARRAY_TASK_COUNT" $header ${GRADE_OPTIONS:-}
