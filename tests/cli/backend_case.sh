#!/usr/bin/env bash
# The petsc backend against the cholmod backend (docs/parallel.md): a problem run with
# solver.backend = "cholmod", then under `mpirun -np RANKS` with "petsc", must give the
# same event list: the same bonds, modes and cascades in the same order, lambda and f to
# 1e-9 relative (f not where a run held a mechanism: events.sh). Each run checks its own
# equilibria to solver.tolerance (a solve that misses it is redone from a fresh
# factorization, or the run stops with an error).
#
# Usage: backend_case.sh LATFRAC MPIEXEC WORKDIR RANKS PROBLEM [--set ...]
# Needs h5dump (hdf5-tools), as scripts/event-lists.sh does.
set -u
latfrac=$1 mpiexec=$2 work=$3 ranks=$4 problem=$5
shift 5
sets=("$@")
rm -rf -- "$work" && mkdir -p -- "$work" || exit 99
command -v h5dump > /dev/null || { echo "backend_case.sh: needs h5dump" >&2; exit 99; }

source "$(dirname "$0")/events.sh"  # events FILE.h5, same_events A B NAME_A NAME_B

"$latfrac" run "$problem" -o "$work/cholmod" --quiet "${sets[@]}" --set solver.backend=cholmod ||
  { echo "FAIL: the cholmod run failed" >&2; exit 1; }
# In a container Open MPI's shared-memory single copy (CMA, ptrace) may be refused;
# copying through the shared buffers works everywhere.
"$mpiexec" --allow-run-as-root --oversubscribe --mca btl_vader_single_copy_mechanism none \
  -np "$ranks" -x OPENBLAS_NUM_THREADS=1 \
  "$latfrac" run "$problem" -o "$work/petsc" --quiet "${sets[@]}" --set solver.backend=petsc ||
  { echo "FAIL: the petsc run on $ranks ranks failed" >&2; exit 1; }
a=$(ls "$work"/cholmod/*.h5) b=$(ls "$work"/petsc/*.h5)
events "$a" > "$work/cholmod.txt"
events "$b" > "$work/petsc.txt"
{ held_lambdas "$a"; held_lambdas "$b"; } > "$work/held.txt"
same_events "$work/cholmod.txt" "$work/petsc.txt" cholmod petsc "$work/held.txt"
