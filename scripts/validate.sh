#!/usr/bin/env bash
# Reproduces docs/validation.md: runs the paper's scenes (problems/fig*.toml with the
# overrides each figure needs; contact on, as shipped), the same scenes without contact,
# Fig. 6 at 707 and 500 m, and each figure on the complete model
# (problems/graben-complete-2d.toml with the figure's criterion), draws each at its first
# structure and at its end, and prints the tables of docs/validation.md with the fault
# analysis of every run.
#
#   bash scripts/validate.sh [build-dir] [figure-dir] [work-dir]
#
# build-dir defaults to build/ (the README's build); the pictures go to figure-dir
# (default docs/figures/validation/, the ones the doc shows), the result files and the
# fault analyses (JSON) to work-dir (default out/validation/). About seven minutes on 2 cores.
set -euo pipefail

here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}
figures=${2:-$here/docs/figures/validation}
out=${3:-$here/out/validation}
latfrac=$build/latfrac
problems=$here/problems
[[ -x $latfrac ]] || { echo "validate.sh: no latfrac binary in $build (build first)" >&2; exit 2; }
mkdir -p "$out" "$figures"

# The first structure (lambda = 5e-4, one increment before the paper's first step ends)
# and the paper's final state.
early=0.0005
snapshots="output.snapshots=[$early, 0.001, 0.02, 0.04]"

# run ID FILE [--set KEY=VALUE ...]: one scene; pictures and fault analyses in $out/ID*.
run() {
  local id=$1 file=$2
  shift 2
  rm -rf "${out:?}/$id"
  local start=$SECONDS
  "$latfrac" run "$problems/$file" -o "$out/$id" --quiet --set "$snapshots" "$@"
  local seconds=$((SECONDS - start))
  local h5
  h5=$(ls "$out/$id"/*.h5)
  local last
  last=$("$latfrac" analyze "$h5" --json | python3 -c 'import json,sys; print(json.load(sys.stdin)["final_lambda"])')
  for lambda in $early "$last"; do
    "$latfrac" render "$h5" --lambda "$lambda" -o "$figures/$id-$lambda.png" --width 900 > /dev/null
    "$latfrac" analyze "$h5" --lambda "$lambda" --json > "$out/$id-$lambda.json"
  done
  python3 - "$id" "$seconds" "$early" "$out/$id-$early.json" "$out/$id-$last.json" <<'EOF'
import json, sys
rid, seconds, early, paths = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4:]
cells = []
for path in paths:
    r = json.load(open(path))["faults"]
    # A fixed-step run takes a snapshot at the first step that reaches it: say so.
    taken = f"(taken at {r['lambda']:g}) " if path == paths[0] and abs(r["lambda"] - early) > 1e-12 else ""
    faults = [f for f in r["faults"] if not f["diffuse"]]
    diffuse = sum(f["bonds"] for f in r["faults"] if f["diffuse"])
    angles = ", ".join(f"{f['alpha_deg']:.1f}" for f in faults[:4]) or "-"
    graben = r.get("graben")
    gtext = ("graben: " + " / ".join(f"dip {f['dip_deg']:.1f} to {f['side']}" for f in graben["faults"])
             if graben else "no graben")
    cells.append(f"{taken}{r['broken_bonds']} broken; {len(faults)} faults (alpha {angles}); "
                 f"{diffuse} in diffuse clusters; {gtext}")
print(f"| {rid} | {cells[0]} | {cells[1]} | {seconds} s |")
EOF
}

echo "| run | at lambda = $early | at the end | wall |"
echo "|---|---|---|---|"
m3="strength.tau0_factor=3"
# Fig. 4a as shipped uses the critical-plane reading; the other two readings for comparison.
run fig4a-fixed fig4a-tensile-2d.toml
run fig4a-event fig4a-tensile-2d.toml --set stepping.method=event
# ... and its faults at lambda = 1e-3, when the pre-cut's crack is held by the confinement.
"$latfrac" render "$out"/fig4a-event/*.h5 --lambda 0.001 -o "$figures/fig4a-event-0.001.png" \
  --width 900 > /dev/null
run fig4a-strain fig4a-tensile-2d.toml --set stepping.method=event --set strength.bond_stress=strain
run fig4a-tensor fig4a-tensile-2d.toml --set stepping.method=event --set strength.bond_stress=tensor
run fig4b-fixed fig4b-tensile-or-shear-2d.toml
run fig4b-m1 fig4b-tensile-or-shear-2d.toml --set strength.tau0_factor=1
run fig6-fixed fig6-elliptic-graben-2d.toml
run fig6-event fig6-elliptic-graben-2d.toml --set stepping.method=event
run fig6-m12-tensor fig6-elliptic-graben-2d.toml --set stepping.method=event \
  --set strength.tau0_factor=12 --set strength.bond_stress=tensor
run fig6-m8-critical fig6-elliptic-graben-2d.toml --set stepping.method=event \
  --set strength.tau0_factor=8 --set strength.bond_stress=critical_plane
run fig7a-fixed fig6-elliptic-graben-2d.toml --set strength.friction_angle=30
run fig7b-fixed fig6-elliptic-graben-2d.toml --set strength.friction_angle=45
run fig7c-fixed fig7c-drucker-prager-2d.toml
run fig7d-event fig7c-drucker-prager-2d.toml --set stepping.method=event
# Shear alone: tensile_or_shear with a tensile strength that is never reached and the
# tau0 of the other scenes (m = 3, psi = 34 deg) given directly.
run fig7f-shear fig4b-tensile-or-shear-2d.toml --set strength.sigma0=1e15 \
  --set strength.tau0_factor=1 --set strength.tau0=141.05e6
run fig8-fixed fig6-elliptic-graben-2d.toml --set lattice.size=[60e3,15e3] \
  --set loading.total=0.02 --set 'output.snapshots=[0.0005,0.001,0.01,0.02]' \
  --set 'precut=[{from=[30250,15900],to=[30250,10e3]}]'
run reference-3d reference-3d.toml

# The paper's scenes without contact: a broken bond carries nothing.
echo
echo "| run (no contact) | at lambda = $early | at the end | wall |"
echo "|---|---|---|---|"
off="contact.enabled=false"
run fig4a-fixed-nocontact fig4a-tensile-2d.toml --set $off
run fig4a-strain-nocontact fig4a-tensile-2d.toml --set $off --set stepping.method=event \
  --set strength.bond_stress=strain
run fig4b-fixed-nocontact fig4b-tensile-or-shear-2d.toml --set $off
run fig6-fixed-nocontact fig6-elliptic-graben-2d.toml --set $off
run fig6-event-nocontact fig6-elliptic-graben-2d.toml --set $off --set stepping.method=event
run fig7c-fixed-nocontact fig7c-drucker-prager-2d.toml --set $off
run reference-3d-nocontact reference-3d.toml --set $off

# Fig. 6 with contact, event-driven, and Figs 4a, 4b and 7c as shipped (fixed), at finer
# spacings (the pre-cut moved with the spacing: a quarter spacing right of 30 km, from
# above the surface row to 25 km).
echo
echo "| run (spacing) | at lambda = $early | at the end | wall |"
echo "|---|---|---|---|"
run fig6-event-707 fig6-elliptic-graben-2d.toml --set stepping.method=event \
  --set lattice.spacing=707.1 --set 'precut=[{from=[30176.8,30700],to=[30176.8,25e3]}]'
run fig6-event-500 fig6-elliptic-graben-2d.toml --set stepping.method=event \
  --set lattice.spacing=500 --set 'precut=[{from=[30125,30400],to=[30125,25e3]}]'
for scene in fig4a-tensile-2d fig4b-tensile-or-shear-2d fig7c-drucker-prager-2d; do
  short=${scene%%-*}
  run "$short-fixed-707" "$scene.toml" --set lattice.spacing=707.1 \
    --set 'precut=[{from=[30176.8,30700],to=[30176.8,25e3]}]'
  run "$short-fixed-500" "$scene.toml" --set lattice.spacing=500 \
    --set 'precut=[{from=[30125,30400],to=[30125,25e3]}]'
done
run fig6-psi30-event fig6-elliptic-graben-2d.toml --set stepping.method=event \
  --set strength.friction_angle=30
run fig6-psi20-event fig6-elliptic-graben-2d.toml --set stepping.method=event \
  --set strength.friction_angle=20
run fig6-psi45-event fig6-elliptic-graben-2d.toml --set stepping.method=event \
  --set strength.friction_angle=45

# The same figures on latfrac's complete model (problems/graben-complete-2d.toml: random
# lattice, internal and contact friction, the basal discontinuity, no pre-cut), with each
# figure's criterion and parameters. Criteria with their own pressure term (tensile,
# Drucker-Prager) take no internal friction.
echo
echo "| run (complete model) | at lambda = $early | at the end | wall |"
echo "|---|---|---|---|"
complete=graben-complete-2d.toml
run complete-4a $complete --set strength.criterion=tensile --set strength.internal_friction=0 \
  --set strength.bond_stress=critical_plane
run complete-4b $complete --set strength.criterion=tensile_or_shear
run complete-6 $complete
run complete-7a $complete --set strength.friction_angle=30
run complete-7b $complete --set strength.friction_angle=45
run complete-7c $complete --set strength.criterion=drucker_prager --set strength.internal_friction=0 \
  --set strength.friction_angle=30 --set strength.tau0_factor=5
run complete-7f $complete --set strength.criterion=tensile_or_shear --set strength.sigma0=1e15 \
  --set strength.tau0_factor=1 --set strength.tau0=141.05e6
run complete-8 $complete --set lattice.size=[60e3,15e3] --set loading.total=0.02 \
  --set 'output.snapshots=[0.0005,0.001,0.01,0.02]'
run complete-3d graben-complete-3d.toml
