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
