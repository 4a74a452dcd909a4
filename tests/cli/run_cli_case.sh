#!/usr/bin/env bash
# Runs one latfrac command-line case and checks what it did (tests/cli/CMakeLists.txt).
#
# Usage: run_cli_case.sh [options] STATUS STDERR_REGEX OUTDIR COMMAND [ARG...]
#
#   STATUS        the exit status the command must return (0, 1 or 2)
#   STDERR_REGEX  an extended regex the whole stderr must match, or "-" for no check
#   OUTDIR        a directory that must NOT exist afterwards (it is removed first), or "-"
#
# The command runs with a 120 s timeout. Whatever STATUS says, an exit status of 124
# (timeout) or >= 128 (killed by a signal: a crash) is a failure. No *.h5, *.xmf, *.png
# or *.partial file may be left in OUTDIR.
#
# Options (before STATUS):
#   --stdout REGEX         the whole stdout must match REGEX
#   --json                 stdout must be one parseable JSON document
#   --one-line             stderr must be exactly one line (the interface's error format)
#   --workdir DIR          run in DIR, removed and created empty first
#   --expect-empty DIR     DIR must exist and be empty afterwards (nothing written)
#   --mkdir DIR            create DIR first (e.g. the directory a picture goes to)
#   --expect-file PATH     PATH must exist afterwards (repeatable)
#   --expect-results DIR/NAME
#                          DIR/NAME.h5, .xmf and .png must exist and no *.partial in DIR;
#                          DIR is removed first
#   --accept-refusal REGEX a TEMPORARY allowance: exit status 2 with stderr matching
#                          REGEX also passes (and skips --expect-results); see CMakeLists.txt
set -u

stdout_regex="" want_json=0 one_line=0 workdir="" accept_refusal=""
expect_empty=() expect_files=() expect_results=()
while [[ $# -gt 0 && $1 == --* ]]; do
  case $1 in
    --stdout) stdout_regex=$2; shift 2 ;;
    --json) want_json=1; shift ;;
    --one-line) one_line=1; shift ;;
    --workdir) workdir=$2; shift 2 ;;
    --expect-empty) expect_empty+=("$2"); shift 2 ;;
    --mkdir) mkdir -p -- "$2" || exit 99; shift 2 ;;
    --expect-file) expect_files+=("$2"); shift 2 ;;
    --expect-results) expect_results+=("$2"); shift 2 ;;
    --accept-refusal) accept_refusal=$2; shift 2 ;;
    *) echo "run_cli_case.sh: unknown option '$1'" >&2; exit 99 ;;
  esac
done
if [[ $# -lt 4 ]]; then
  echo "usage: run_cli_case.sh [options] STATUS STDERR_REGEX OUTDIR COMMAND [ARG...]" >&2
  exit 99
fi
expected_status=$1 stderr_regex=$2 outdir=$3
shift 3

failures=()
fail() { failures+=("$1"); }

# Start from a clean slate, so a stale file never makes a case pass or fail.
[[ $outdir != - ]] && rm -rf -- "$outdir"
for results in "${expect_results[@]}"; do rm -rf -- "$(dirname -- "$results")"; done
for file in "${expect_files[@]}"; do rm -f -- "$file"; done
if [[ -n $workdir ]]; then
  rm -rf -- "$workdir" && mkdir -p -- "$workdir" || { echo "cannot create $workdir" >&2; exit 99; }
fi

scratch=$(mktemp -d) || exit 99
trap 'rm -rf -- "$scratch"' EXIT
(
  [[ -n $workdir ]] && cd -- "$workdir"
  exec timeout --kill-after=10 120 "$@"
) >"$scratch/stdout" 2>"$scratch/stderr" </dev/null
status=$?
stdout=$(<"$scratch/stdout")
stderr=$(<"$scratch/stderr")

refused=0
if [[ $status -eq 124 ]]; then
  fail "timed out after 120 s"
elif [[ $status -ge 128 ]]; then
  fail "killed by signal $((status - 128)) (exit status $status): a crash"
elif [[ $status -eq 126 || $status -eq 127 ]]; then
  fail "could not execute the command (exit status $status)"
elif [[ -n $accept_refusal && $status -eq 2 && $expected_status -ne 2 && $stderr =~ $accept_refusal ]]; then
  refused=1
  echo "note: accepted the temporary refusal (exit status 2, stderr matches /$accept_refusal/)"
elif [[ $status -ne $expected_status ]]; then
  fail "exit status $status, expected $expected_status"
fi

if [[ $refused -eq 0 && $stderr_regex != - && ! $stderr =~ $stderr_regex ]]; then
  fail "stderr does not match the regex: $stderr_regex"
fi
if [[ $one_line -eq 1 ]]; then
  lines=$(printf '%s' "$stderr" | grep -c '')
  [[ $lines -eq 1 ]] || fail "stderr has $lines lines, expected exactly one error line"
fi
if [[ $refused -eq 0 && -n $stdout_regex && ! $stdout =~ $stdout_regex ]]; then
  fail "stdout does not match the regex: $stdout_regex"
fi
if [[ $refused -eq 0 && $want_json -eq 1 ]]; then
  if ! python3 -c 'import json, sys; json.load(sys.stdin)' <"$scratch/stdout" 2>"$scratch/json"; then
    fail "stdout is not valid JSON: $(tail -n 1 "$scratch/json")"
  fi
fi

# Files left behind.
leftovers() {
  find "$1" \( -name '*.h5' -o -name '*.xmf' -o -name '*.png' -o -name '*.partial' \
    -o -name '*.h5.*' -o -name '*.xmf.*' -o -name '*.png.*' \) 2>/dev/null
}
if [[ $outdir != - && -e $outdir ]]; then
  left=$(leftovers "$outdir")
  if [[ -n $left ]]; then
    fail "result files were left in $outdir: $(echo $left)"
  else
    fail "$outdir exists afterwards (nothing may be written on failure)"
  fi
fi
for dir in "${expect_empty[@]}"; do
  if [[ ! -d $dir ]]; then
    fail "$dir no longer exists"
  elif [[ -n $(ls -A -- "$dir") ]]; then
    fail "files were written to $dir: $(ls -A -- "$dir" | tr '\n' ' ')"
  fi
done
for file in "${expect_files[@]}"; do
  [[ -s $file ]] || fail "$file was not written (or is empty)"
done
for results in "${expect_results[@]}"; do
  if [[ $refused -eq 1 ]]; then
    left=$(leftovers "$(dirname -- "$results")")
    [[ -z $left ]] || fail "the refused run left result files: $(echo $left)"
    continue
  fi
  for ext in h5 xmf png; do
    [[ -s $results.$ext ]] || fail "$results.$ext was not written (or is empty)"
  done
  partial=$(find "$(dirname -- "$results")" -name '*partial*' 2>/dev/null)
  [[ -z $partial ]] || fail "temporary files were left: $(echo $partial)"
done

if [[ ${#failures[@]} -gt 0 ]]; then
  echo "FAILED: $(printf '%q ' "$@")"
  [[ -n $workdir ]] && echo "  (in $workdir)"
  for failure in "${failures[@]}"; do echo "  - $failure"; done
  echo "  exit status: $status"
  echo "  --- stdout (first 40 lines) ---"
  head -n 40 "$scratch/stdout"
  echo "  --- stderr (first 40 lines) ---"
  head -n 40 "$scratch/stderr"
  exit 1
fi
echo "ok: exit status $status: $(printf '%q ' "$@")"
[[ -n $stderr ]] && echo "stderr: $stderr"
exit 0
