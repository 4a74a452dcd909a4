#!/usr/bin/env bash
# Writes the event list of every shipped problem, run fixed-step and event-driven, with
# and without contact, as text: for checking that a change leaves every result alone.
#
#   bash scripts/event-lists.sh [build-dir] [out-dir]      # then: diff -r OLD NEW
#
# Each run's /events datasets (lambda to 17 digits, bond, f, mode, cascade) go to
# out-dir/<problem>-<method>[-contact].txt. Needs h5dump (Debian's hdf5-tools). About two
# minutes on 2 cores.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}
out=${2:-$here/out/event-lists}
latfrac=$build/latfrac
[[ -x $latfrac ]] || { echo "event-lists.sh: no latfrac binary in $build" >&2; exit 2; }
command -v h5dump > /dev/null || { echo "event-lists.sh: needs h5dump (apt-get install hdf5-tools)" >&2; exit 2; }
mkdir -p "$out"
for problem in "$here"/problems/*.toml; do
  stem=$(basename "$problem" .toml)
  for method in fixed event; do
    for contact in "" "-contact"; do
      extra=(--set stepping.method=$method)
      [[ $method == fixed ]] && ! grep -q '^increment' "$problem" && extra+=(--set stepping.increment=1e-3)
      if [[ -n $contact ]]; then extra+=(--set contact.enabled=true)
      elif grep -q "^\[contact\]" "$problem"; then
        # A friction (or its facets) on a disabled contact is an error: the whole table
        # is replaced.
        extra+=(--set 'contact={enabled=false}')
      fi
      # An elastic scene (no [strength]) has no events; contact needs a [strength].
      grep -q '^\[strength\]' "$problem" || { [[ -z $contact && $method == event ]] || continue; }
      dir=$(mktemp -d)
      "$latfrac" run "$problem" -o "$dir" --quiet "${extra[@]}" > /dev/null
      h5=$(ls "$dir"/*.h5)
      h5dump -m '%.17g' -d /events/lambda -d /events/bond -d /events/f -d /events/mode \
        -d /events/cascade "$h5" | grep -v '^HDF5 "' > "$out/$stem-$method$contact.txt"
      rm -rf "$dir"
      echo "$stem-$method$contact: $(grep -c , "$out/$stem-$method$contact.txt" || true) lines"
    done
  done
done
