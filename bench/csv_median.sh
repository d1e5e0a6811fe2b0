#!/bin/sh
# csv_median.sh: one convergence series from several runs of it (e.g. seeds
# of `cavalry_bench --converge`): per spp row, the median of every column
# over the runs, so that one outlier run (a firefly in relMSE, a slow GPU
# pass) does not decide a comparison. All inputs must have the same header
# and spp rows.
#
# usage: bench/csv_median.sh RUN.csv... > MEDIAN.csv
set -eu
[ $# -gt 0 ] || { echo "usage: csv_median.sh RUN.csv... > MEDIAN.csv" >&2; exit 2; }
awk -F, -v runs=$# '
FNR == 1 { if (NR == 1) print; else if ($0 != header) { print "csv_median.sh: " FILENAME ": header differs" > "/dev/stderr"; bad = 1; exit 1 } header = $0; next }
{ row[FNR] = 1; for (c = 1; c <= NF; c++) v[FNR, c, ++n[FNR, c]] = $c; cols = NF; if (FNR > last) last = FNR }
END {
    if (bad) exit 1
    for (r = 2; r <= last; r++) {
        line = ""
        for (c = 1; c <= cols; c++) {
            k = n[r, c]
            if (k != runs) { print "csv_median.sh: row " r " is not in every run" > "/dev/stderr"; exit 1 }
            for (i = 1; i <= k; i++) a[i] = v[r, c, i] + 0
            for (i = 2; i <= k; i++) { x = a[i]; for (j = i - 1; j >= 1 && a[j] > x; j--) a[j + 1] = a[j]; a[j + 1] = x }
            m = (k % 2) ? a[(k + 1) / 2] : (a[k / 2] + a[k / 2 + 1]) / 2
            line = line (c > 1 ? "," : "") sprintf("%.6g", m)
        }
        print line
    }
}' "$@"
