#!/usr/bin/env bash
# Command-line tests of runs written as they go (docs/restart.md): SIGTERM and SIGKILL at
# random moments (after the file first appears) leave a readable result file whose resume gives the uninterrupted event
# list; a changed problem is refused; a full disk and a locked file give a message, exit 1
# and keep the last checkpoint.
#
# Usage: restart_case.sh LATFRAC WORKDIR CASE PROBLEM [--set ...]
#   CASE: signals:SEED[,SEED...] (SIGTERM and SIGKILL at moments drawn from each seed) |
#         refuse-changed | full-disk | locked
# Needs h5dump (hdf5-tools), as scripts/event-lists.sh does.
set -u
latfrac=$1 work=$2 case=$3 problem=$4
shift 4
sets=("$@")
rm -rf -- "$work" && mkdir -p -- "$work" || exit 99
command -v h5dump > /dev/null || { echo "restart_case.sh: needs h5dump" >&2; exit 99; }
name=$(sed -n 's/^name *= *"\([^"]*\)".*/\1/p' "$problem" | head -1)
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }

source "$(dirname "$0")/events.sh"  # events FILE.h5: one line per event

# Same bonds, modes and cascades in the same order, lambdas and f to 1e-12 relative.
same_events() {
  paste -d ' ' <(events "$1") <(events "$2") | awk '
    function off(a, b) { d = a - b; if (d < 0) d = -d; m = b < 0 ? -b : b; return d > 1e-12 * m }
    NF != 10 || $2 != $7 || $4 != $9 || $5 != $10 || off($1, $6) || off($3, $8) { bad = NR }
    END { if (bad) { print "events differ from line " bad > "/dev/stderr"; exit 1 } }' &&
    [[ $(events "$1" | wc -l) == $(events "$2" | wc -l) ]]
}

complete_flag() { h5dump -a /summary/complete "$1" 2>/dev/null | awk '/\(0\)/ { print $2 }'; }

run_whole() {
  local start=$(date +%s.%N)
  "$latfrac" run "$problem" -o "$work/whole" --quiet "${sets[@]}" > /dev/null 2>&1 ||
    { fail "the uninterrupted run failed"; exit 1; }
  whole_seconds=$(echo "$(date +%s.%N) - $start" | bc)
}

# Starts a run in the background with checkpoints every 60 ms; its pid in $run_pid.
start_run() {
  "$latfrac" run "$problem" -o "$1" --quiet --checkpoint-every 0.001 "${sets[@]}" \
    > "$1.out" 2> "$1.err" &
  run_pid=$!
}

wait_for_file() {
  for _ in $(seq 200); do [[ -f $1 ]] && return 0; sleep 0.02; done
  return 1
}

case $case in
signals:*)
  run_whole
  for seed in ${case#signals:}; do
    for signal in TERM KILL; do
      dir=$work/$signal-$seed h5=$work/$signal-$seed/$name.h5
      RANDOM=$((seed * 7 + ${#signal}))
      delay=$(echo "scale=3; $whole_seconds * (0.15 + 0.7 * $RANDOM / 32767)" | bc)
      start_run "$dir"
      wait_for_file "$h5"
      sleep "$delay"
      kill -s "$signal" "$run_pid" 2> /dev/null
      wait "$run_pid"
      status=$?
      label="SIG$signal after $delay s (seed $seed, status $status)"
      if [[ $(complete_flag "$h5") == 1 ]]; then  # finished before the signal came
        same_events "$h5" "$work/whole/$name.h5" || fail "$label: finished, events differ"
        echo "$label: had finished"
        continue
      fi
      [[ $signal == TERM && $status != 3 ]] && fail "$label: a clean stop exits with 3"
      [[ $signal == KILL && $status != 137 ]] && fail "$label: expected death by SIGKILL"
      [[ -f $h5 ]] || { fail "$label: no result file"; continue; }
      "$latfrac" analyze "$h5" > /dev/null 2>&1 || fail "$label: latfrac analyze cannot read $h5"
      [[ $(complete_flag "$h5") == 0 ]] || fail "$label: the file does not say it is incomplete"
      [[ $signal == TERM ]] && ! grep -q "latfrac run --resume $h5" "$dir.err" &&
        fail "$label: no resume hint on stderr"
      "$latfrac" run --resume "$h5" --quiet > /dev/null 2> "$dir.resume.err" ||
        { fail "$label: resume failed: $(cat "$dir.resume.err")"; continue; }
      [[ $(complete_flag "$h5") == 1 ]] || fail "$label: resumed file not complete"
      same_events "$h5" "$work/whole/$name.h5" || fail "$label: resumed events differ"
      echo "$label: resumed, same events"
    done
  done
  ;;
refuse-changed)
  cp "$problem" "$work/problem.toml" && problem=$work/problem.toml
  h5=$work/stopped/$name.h5
  # A short run can finish before the signal lands (status 0, seen under load): run again.
  for _ in 1 2 3 4 5; do
    rm -rf -- "$work/stopped"
    start_run "$work/stopped"
    wait_for_file "$h5"
    kill -s TERM "$run_pid"; wait "$run_pid"
    status=$?
    [[ $status == 0 ]] || break
  done
  [[ $status == 3 ]] || { fail "the run did not stop cleanly: status $status, $(cat "$work/stopped.err")"; exit 1; }
  # Stopped at once, mostly before its first snapshot: analyze --json still prints JSON,
  # and says the file is not complete.
  "$latfrac" analyze --json "$h5" 2> /dev/null |
    python3 -c 'import json, sys; sys.exit(json.load(sys.stdin)["complete"] is not False)' ||
    fail "analyze --json on the stopped file does not print JSON with \"complete\": false"
  # No NaN in a checkpoint either (a "none" lambda is written as 0 with a flag).
  h5dump -A "$h5" | grep -qiw nan && fail "the stopped file holds a NaN attribute"
  sed -i '1i # an edit after the run started' "$problem"
  "$latfrac" run --resume "$h5" --quiet > /dev/null 2> "$work/refused.err"
  status=$?
  [[ $status == 2 ]] || fail "a changed problem: status $status, expected 2"
  grep -q "differs from the problem the run started with" "$work/refused.err" ||
    fail "a changed problem: message was: $(cat "$work/refused.err")"
  sed -i '1d' "$problem"
  "$latfrac" run --resume "$h5" --quiet --set lattice.spacing=1234 > /dev/null 2> "$work/sets.err"
  [[ $? == 2 ]] && grep -qF "overrides differ from those the run started with (${sets[*]})" \
    "$work/sets.err" || fail "changed --set: $(cat "$work/sets.err")"
  # Not even --force resumes with another increment (the checkpoint counts steps of the
  # old one) or a total on the other side of the lambda it has reached.
  for change in "stepping.increment=0.01" "loading.total=-0.01"; do
    "$latfrac" run --resume "$h5" --quiet --force "${sets[@]}" --set "$change" \
      --set 'output.snapshots=[]' > /dev/null 2> "$work/forced.err"
    [[ $? == 2 ]] && grep -q "even with --force" "$work/forced.err" ||
      fail "--force with $change: $(cat "$work/forced.err")"
  done
  [[ $(complete_flag "$h5") == 0 ]] || fail "a refused resume changed the file"
  "$latfrac" run --resume "$h5" --quiet > /dev/null 2> "$work/resume.err" ||
    fail "the unchanged problem: resume failed: $(cat "$work/resume.err")"
  ;;
full-disk)
  run_whole
  # A file-size limit (ulimit -f, 1 KiB blocks) that the file at the start fits and the
  # complete one does not: some checkpoint fails with EFBIG.
  h5=$work/full/$name.h5
  start_run "$work/probe"
  wait_for_file "$work/probe/$name.h5"; sleep 0.05
  kill -s KILL "$run_pid"; wait "$run_pid" 2> /dev/null
  first=$(stat -c %s "$work/probe/$name.h5") last=$(stat -c %s "$work/whole/$name.h5")
  limit=$(((first + last) / 2 / 1024))
  (ulimit -f "$limit"
   exec "$latfrac" run "$problem" -o "$work/full" --quiet --checkpoint-every 0.0005 "${sets[@]}") \
    > /dev/null 2> "$work/full.err"
  status=$?
  [[ $status == 1 ]] || fail "full disk: status $status, expected 1"
  grep -qi "file too large" "$work/full.err" || fail "full disk: message was: $(cat "$work/full.err")"
  grep -q "last checkpoint written is intact" "$work/full.err" ||
    fail "full disk: the message does not say the checkpoint is kept"
  [[ $(wc -l < "$work/full.err") == 1 ]] || fail "full disk: more than one line on stderr"
  "$latfrac" analyze "$h5" > /dev/null 2>&1 || fail "full disk: the last checkpoint is not readable"
  [[ $(complete_flag "$h5") == 0 ]] || fail "full disk: the file says it is complete"
  "$latfrac" run --resume "$h5" --quiet > /dev/null 2> "$work/resume.err" ||
    fail "full disk: resume failed: $(cat "$work/resume.err")"
  same_events "$h5" "$work/whole/$name.h5" || fail "full disk: resumed events differ"
  ;;
locked)
  h5=$work/first/$name.h5
  start_run "$work/first"
  wait_for_file "$h5"
  "$latfrac" run "$problem" -o "$work/first" --quiet "${sets[@]}" > /dev/null 2> "$work/second.err"
  status=$?
  kill -s TERM "$run_pid" 2> /dev/null; wait "$run_pid"
  [[ $status == 1 ]] || fail "locked: status $status, expected 1"
  grep -q "is being written by another latfrac run" "$work/second.err" ||
    fail "locked: message was: $(cat "$work/second.err")"
  "$latfrac" analyze "$h5" > /dev/null 2>&1 || fail "locked: the first run's file is not readable"
  ;;
*) echo "restart_case.sh: unknown case '$case'" >&2; exit 99 ;;
esac
[[ $failures == 0 ]] && echo "ok: $case"
exit $((failures > 0))
