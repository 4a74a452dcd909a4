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

# same_events A.txt B.txt NAME_A NAME_B: whether two event lists (from `events`) are the
# same: the same bonds, modes and cascades in the same order, lambda and f to 1e-9
# relative. Prints the first difference, or the count and the largest relative
# difference of lambda; returns 1 if they differ.
same_events() {
  local count
  count=$(wc -l < "$1")
  [[ $count -gt 0 ]] || { echo "FAIL: $3 has no events" >&2; return 1; }
  [[ $count == $(wc -l < "$2") ]] ||
    { echo "FAIL: $count events with $3, $(wc -l < "$2") with $4" >&2; return 1; }
  paste -d ' ' "$1" "$2" | awk -v a="$3" -v b="$4" '
    function off(x, y) { d = x - y; if (d < 0) d = -d; m = x < 0 ? -x : x; n = y < 0 ? -y : y;
                         if (n > m) m = n; return d > 1e-9 * m }
    function rel(x, y) { d = x - y; if (d < 0) d = -d; m = x < 0 ? -x : x; return m > 0 ? d / m : d }
    { if (rel($1, $6) > worst) worst = rel($1, $6) }
    NF != 10 || $2 != $7 || $4 != $9 || $5 != $10 || off($1, $6) || off($3, $8) {
      print "FAIL: events differ from event " NR ": " a " " $1, $2, $3, $4, $5 ", " b " " $6, $7, $8, $9, $10 > "/dev/stderr"; exit 1 }
    END { printf "%d events equal; largest relative difference of lambda %.2g\n", NR, worst }'
}
