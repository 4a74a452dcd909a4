# Sourced by the CLI test scripts: events FILE.h5 prints a result file's events, one per
# line: lambda bond f mode cascade (lambda and f to 17 digits). Needs h5dump (hdf5-tools).
events() {
  h5dump -m '%.17g' -w 0 -d /events/lambda -d /events/bond -d /events/f -d /events/mode \
    -d /events/cascade "$1" |
    awk '/DATASET/ { name = $2; n = 0 }
         /^ *\([0-9]+\): / { sub(/^ *\([0-9]+\): /, ""); gsub(/,/, " ");
                              for (i = 1; i <= NF; i++) v[name, n++] = $i; count[name] = n }
         END { k = "\"/events/lambda\""; for (i = 0; i < count[k]; i++)
                 print v[k, i], v["\"/events/bond\"", i], v["\"/events/f\"", i],
                       v["\"/events/mode\"", i], v["\"/events/cascade\"", i] }'
}

# held_lambdas FILE.h5: the lambdas at which the run held a part or a mechanism
# (/fragments/lambda, to 17 digits), one per line; nothing when it held none.
held_lambdas() {
  h5dump -m '%.17g' -w 0 -d /fragments/lambda "$1" 2> /dev/null |
    awk '/^ *\([0-9]+\): / { sub(/^ *\([0-9]+\): /, ""); gsub(/,/, " ");
                              for (i = 1; i <= NF; i++) print $i }'
}

# same_events A.txt B.txt NAME_A NAME_B [HELD.txt]: whether two event lists (from
# `events`) are the same: the same bonds, modes and cascades in the same order, lambda
# and f to 1e-9 relative. HELD (from held_lambdas of either run) names the lambdas at
# which a run held a mechanism: there a nearly singular stiffness may be found singular
# by one factorization (a pivot rounded below zero) and not by another (another
# ordering, another backend, another CPU's BLAS), so the run that holds it reads the
# cascade's later f on a state with one more unknown held (docs/robustness.md,
# "Safety net"). At those lambdas a cascade's break (f > 1 in both) must only be the same
# bond, in the same order; its f is not compared. Prints the first difference, or the
# count and the largest relative difference of lambda; returns 1 if they differ.
same_events() {
  local count held=${5:-/dev/null}
  count=$(wc -l < "$1")
  [[ $count -gt 0 ]] || { echo "FAIL: $3 has no events" >&2; return 1; }
  [[ $count == $(wc -l < "$2") ]] ||
    { echo "FAIL: $count events with $3, $(wc -l < "$2") with $4" >&2; return 1; }
  paste -d ' ' "$1" "$2" | awk -v a="$3" -v b="$4" -v heldfile="$held" '
    BEGIN { while ((getline line < heldfile) > 0) held[line] = 1 }
    function off(x, y) { d = x - y; if (d < 0) d = -d; m = x < 0 ? -x : x; n = y < 0 ? -y : y;
                         if (n > m) m = n; return d > 1e-9 * m }
    function rel(x, y) { d = x - y; if (d < 0) d = -d; m = x < 0 ? -x : x; return m > 0 ? d / m : d }
    function loose(x, y) { return (($1 in held) || ($6 in held)) && x > 1 + 1e-6 && y > 1 + 1e-6 }
    { if (rel($1, $6) > worst) worst = rel($1, $6) }
    NF != 10 || $2 != $7 || $4 != $9 || $5 != $10 || off($1, $6) || (off($3, $8) && !loose($3, $8)) {
      print "FAIL: events differ from event " NR ": " a " " $1, $2, $3, $4, $5 ", " b " " $6, $7, $8, $9, $10 > "/dev/stderr"; failed = 1; exit 1 }
    off($3, $8) { relaxed++ }
    END { if (failed) exit 1
          printf "%d events equal; largest relative difference of lambda %.2g", NR, worst
          if (relaxed) printf "; f of %d cascade breaks not compared (a mechanism held at their lambda)", relaxed
          printf "\n" }'
}
