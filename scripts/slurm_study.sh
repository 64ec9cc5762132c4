#!/bin/bash
# A study across the nodes of a Slurm allocation. Every task runs the same
# script; rank 0 hands out rows and is the only process that opens the
# SQLite database. Submit with:
#   sbatch scripts/slurm_study.sh [script] [db] [csv]
# A job that hits its time limit (or is cancelled, or a node dies) keeps
# every finished run: submit it again and only the unfinished rows run.
# Two minutes before the limit Slurm sends SIGTERM to every task
# (--signal below): each rank stops at a safe point ("terminated
# (SIGTERM)"), the rows it finished are in the database, and it ends by
# SIGTERM; scancel does the same at once.
#SBATCH --job-name=ashlar-study
#SBATCH --nodes=2
#SBATCH --ntasks-per-node=32      # one rank per core: each rank runs one row at a time
#SBATCH --cpus-per-task=1
#SBATCH --time=02:00:00
#SBATCH --output=ashlar-study-%j.log
#SBATCH --signal=TERM@120
set -euo pipefail

ashlar=${ASHLAR:-"$SLURM_SUBMIT_DIR/build/bin/ashlar"}
script=${1:-"$SLURM_SUBMIT_DIR/scripts/arch_sweep.lua"}
# Only rank 0 writes the database, so it needs a filesystem with working
# POSIX locks where rank 0 runs (node-local disk, Lustre, GPFS); copy it
# back at the end if it lives on node-local scratch.
db=${2:-"$SLURM_SUBMIT_DIR/arch.sqlite"}
csv=${3:-"$SLURM_SUBMIT_DIR/arch.csv"}

# The progress line becomes plain log lines in the job's output file.
# Use `mpirun "$ashlar" ...` instead where Slurm's MPI plugin is not set up.
srun --mpi=pmix "$ashlar" "$script" "$db" 1 "$csv"
