#!/usr/bin/env bash
# Measures the faults issue's targets on the complete model (docs/validation.md, "Anderson's
# dip, measured"): runs problems/graben-complete-2d.toml (or the file given) for each
# friction angle phi and lattice seed, with the intact bonds' internal friction and the
# contacts' friction both tan(phi) and the criterion's psi = phi, and prints per run the
# graben's two dips against Anderson's 45 + phi/2 and the share of broken bonds outside
# its faults, and what moves: the fault that carries most of the relative motion among the
# bonds that moved by a twentieth of the base's gap (lambda Lx) or more, its dip and its
# mean opening against that gap (docs/fault-analysis.md, "Offsets: what moves"); then per
# phi and spacing the mean dip over the seeds with its spread.
#
#   bash scripts/anderson-dips.sh [build-dir] [work-dir]
#
# Environment (defaults in brackets): PHIS [25 30 40], SEEDS [1 2 3 4 5], SPACINGS [1000],
# PROBLEM [problems/graben-complete-2d.toml], MIRROR [false]: true runs the mirror image
# (lattice.mirror, the discontinuity at Lx - x_d). Extra --set arguments go in SETS.
# About 10 s per run at 1000 m, 60 s at 707 m, on one core of the 2-core machine.
set -euo pipefail

here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}
out=${2:-$here/out/anderson}
latfrac=$build/latfrac
problem=${PROBLEM:-$here/problems/graben-complete-2d.toml}
phis=${PHIS:-25 30 40}
seeds=${SEEDS:-1 2 3 4 5}
spacings=${SPACINGS:-1000}
mirror=${MIRROR:-false}
[[ -x $latfrac ]] || { echo "anderson-dips.sh: no latfrac binary in $build (build first)" >&2; exit 2; }
mkdir -p "$out"
read -r -a extra <<< "${SETS:-}"

# The discontinuity of the problem file, mirrored when asked.
x_d=$("$latfrac" check "$problem" 2>/dev/null | awk '$1 == "basal_discontinuity" {print $2}')
lx=$("$latfrac" check "$problem" 2>/dev/null | awk '$1 == "size" {gsub(/[\[\],]/, " "); print $2; exit}')
[[ -n $x_d && -n $lx ]] || { echo "anderson-dips.sh: $problem has no basal_discontinuity" >&2; exit 2; }
[[ $mirror == true ]] && x_d=$(python3 -c "print($lx - $x_d)")

rows=$out/rows.tsv
: > "$rows"
echo "| phi deg | Anderson dip | spacing m | seed | broken | graben dips (dips to) | off Anderson deg | share outside the graben's faults | what moves: dip, opening / gap, share of the motion | wall s |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for spacing in $spacings; do
  for phi in $phis; do
    mu=$(python3 -c "import math; print(f'{math.tan(math.radians($phi)):.6f}')")
    for seed in $seeds; do
      id=phi$phi-a$spacing-s$seed-m$mirror
      rm -rf "${out:?}/$id"
      if ! "$latfrac" run "$problem" -o "$out/$id" --quiet --set lattice.seed="$seed" \
        --set lattice.spacing="$spacing" --set lattice.mirror="$mirror" \
        --set loading.basal_discontinuity="$x_d" --set strength.friction_angle="$phi" \
        --set strength.internal_friction="$mu" --set contact.friction="$mu" \
        --set 'output.snapshots=[]' "${extra[@]}"; then
        echo "| $phi | | $spacing | $seed | the run failed (its message above) | | | | | |"
        continue
      fi
      "$latfrac" analyze --json "$out/$id"/*.h5 > "$out/$id.json"
      gap=$(python3 -c "import json, sys; print(json.load(open(sys.argv[1]))['final_lambda'] * $lx)" "$out/$id.json")
      "$latfrac" analyze --json --min-offset "$(python3 -c "print(abs($gap) / 20)")" "$out/$id"/*.h5 \
        > "$out/$id.moved.json"
      python3 - "$out/$id.json" "$phi" "$spacing" "$seed" "$rows" "$out/$id.moved.json" "$gap" <<'EOF'
import json, sys
path, phi, spacing, seed, rows, moved_path, gap = sys.argv[1:]
d = json.load(open(path))
moved = json.load(open(moved_path))["faults"]["faults"]
gap = abs(float(gap))
if moved:
    m = max(moved, key=lambda x: x["motion_share"])
    side = {1: "+x", -1: "-x"}.get(m["dip_direction"], "-")
    moves = f"{m['dip_deg']:.1f} ({side}), {m['opening_m']:.0f} / {gap:.0f} m, {m['motion_share']:.2f}"
else:
    moves = "nothing moved that far"

f = d["faults"]
anderson = 45 + float(phi) / 2
broken = f["broken_bonds"]
g = f["graben"]
if g:
    dips = [(x["dip_deg"], x["side"]) for x in g["faults"]]
    outside = g["share_outside"]
    off = max(abs(dip - anderson) for dip, _ in dips)
    text = " / ".join(f"{dip:.1f} ({side})" for dip, side in dips)
    print(f"| {phi} | {anderson:.1f} | {spacing} | {seed} | {broken} | {text} | {off:.1f} | "
          f"{outside:.2f} | {moves} | {d['wall_seconds']:.0f} |")
    with open(rows, "a") as r:
        r.write(f"{phi}\t{spacing}\t{seed}\t{dips[0][0]}\t{dips[1][0]}\t{outside}\n")
else:
    print(f"| {phi} | {anderson:.1f} | {spacing} | {seed} | {broken} | no graben | - | 1.00 | "
          f"{moves} | {d['wall_seconds']:.0f} |")
    with open(rows, "a") as r:
        r.write(f"{phi}\t{spacing}\t{seed}\tnan\tnan\t1\n")
EOF
    done
  done
done

echo
echo "| phi deg | spacing m | Anderson dip | seeds with a graben | mean dip (min - max) | seeds within 5 deg (both faults) | mean share outside |"
echo "|---|---|---|---|---|---|---|"
python3 - "$rows" <<'EOF'
import math, sys
from collections import defaultdict
groups = defaultdict(list)
for line in open(sys.argv[1]):
    phi, spacing, seed, a, b, outside = line.split("\t")
    groups[(float(phi), spacing)].append((float(a), float(b), float(outside)))
for (phi, spacing), runs in groups.items():
    anderson = 45 + phi / 2
    found = [r for r in runs if not math.isnan(r[0])]
    dips = [d for r in found for d in r[:2]]
    within = sum(1 for r in found if max(abs(r[0] - anderson), abs(r[1] - anderson)) <= 5)
    mean = f"{sum(dips) / len(dips):.1f} ({min(dips):.1f} - {max(dips):.1f})" if dips else "-"
    share = sum(r[2] for r in runs) / len(runs)
    print(f"| {phi:g} | {spacing} | {anderson:.1f} | {len(found)} of {len(runs)} | {mean} | "
          f"{within} of {len(runs)} | {share:.2f} |")
EOF
