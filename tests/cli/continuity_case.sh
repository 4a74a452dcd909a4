#!/usr/bin/env bash
# Event-driven breaking is exact, so its event list is a continuous function of the
# problem's data away from genuine branch points: a problem run as given and with one
# datum changed at the level of rounding (each KEY=VALUE given, say gravity.g 1e-13, 1e-12
# and -1e-11 relative away) must give the same event list (the same bonds, modes,
# cascades and order; lambda and f to 1e-9 relative). A decision left to rounding, such
# as which facet of the friction cone a contact at a corner slips on (docs/robustness.md),
# fails it: one such decision moved a later break by 1.6e-4 in lambda.
#
# Usage: continuity_case.sh LATFRAC WORKDIR KEY=VALUE[,KEY=VALUE...] PROBLEM [--set ...]
# Needs h5dump (hdf5-tools), as scripts/event-lists.sh does.
set -u
latfrac=$1 work=$2 problem=$4
IFS=, read -r -a changes <<< "$3"
shift 4
sets=("$@")
rm -rf -- "$work" && mkdir -p -- "$work" || exit 99
command -v h5dump > /dev/null || { echo "continuity_case.sh: needs h5dump" >&2; exit 99; }
source "$(dirname "$0")/events.sh"  # events FILE.h5, same_events A B NAME_A NAME_B

"$latfrac" run "$problem" -o "$work/given" --quiet "${sets[@]}" ||
  { echo "FAIL: the run as given failed" >&2; exit 1; }
events "$(ls "$work"/given/*.h5)" > "$work/given.txt"
for k in "${!changes[@]}"; do
  changed=${changes[$k]}
  "$latfrac" run "$problem" -o "$work/changed-$k" --quiet "${sets[@]}" --set "$changed" ||
    { echo "FAIL: the run with $changed failed" >&2; exit 1; }
  events "$(ls "$work"/changed-$k/*.h5)" > "$work/changed-$k.txt"
  same_events "$work/given.txt" "$work/changed-$k.txt" given "$changed" || exit 1
done
