#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Measure the throughput of many logs (docs/hpc.md): log-hours per
# core-second of 'swaywatch batch' (replay) on 1 core, on 2 MPI ranks and
# on 2 threads, and of forensics ('batch --job forensics') on 1 core and on 1
# and 2 MPI ranks;
# the parallel efficiency against the 1-core run of the same work.  The
# results replace the measured part of docs/hpc.md.
#   scripts/run-batch-bench.sh          full run (about ten minutes on 2 vCPU)
#   QUICK=1 scripts/run-batch-bench.sh  a smoke run (a tenth of the logs, 1 run)
# Needs a build with MPI (Open MPI: scripts/setup-debian.sh) and the
# benchmarks' log generator (sw_bench gen-csv, bench/).
set -eu
cd "$(dirname "$0")/.."
BUILD=${BUILD:-build-bench}
RUNS=${RUNS:-5}
DOC=docs/hpc.md
cmake -S . -B "$BUILD" -DSW_WERROR=ON -DSW_BUILD_BENCH=ON -DSW_MPI=ON \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$BUILD" -j 2 --target sw_bench swaywatch-cli swaywatch-mpi-cli >/dev/null
SW=$BUILD/swaywatch
SWMPI=$BUILD/swaywatch-mpi # the same command with MPI
GEN=$BUILD/bench/sw_bench
TMP=$(mktemp -d /tmp/sw-batch-bench.XXXXXX)
trap 'rm -rf "$TMP"' EXIT
OUT=$TMP/results.md
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none
SCALE=1
[ -n "${QUICK:-}" ] && SCALE=0.1 RUNS=1
LOAD=$(cut -d' ' -f1-3 /proc/loadavg)

# A fleet's day in small: logs of 3 to 90 minutes at 1 kHz (the road of
# bench_road.c, a seed each), as a truck's logger cuts them at stops.
: >"$TMP/replay.txt"
hours=0
i=0
for m in 3 90 6 45 12 30 20 60 9 15; do
    i=$((i + 1))
    h=$(awk -v m="$m" -v s="$SCALE" 'BEGIN{printf "%.4f", m * s / 60}')
    "$GEN" gen-csv --hours "$h" --seed "$i" >"$TMP/log$i.csv"
    echo "$TMP/log$i.csv" >>"$TMP/replay.txt"
    hours=$(awk -v a="$hours" -v b="$h" 'BEGIN{print a + b}')
done
# forensics: each log replayed some hundreds of times (safety factors of
# the what-if cases): shorter logs, 0.5 to 2 minutes
: >"$TMP/forensics.txt"
fhours=0
for m in 0.5 2 1 1.5; do
    i=$((i + 1))
    h=$(awk -v m="$m" -v s="$SCALE" 'BEGIN{printf "%.4f", m * s / 60}')
    "$GEN" gen-csv --hours "$h" --seed "$i" >"$TMP/log$i.csv"
    echo "$TMP/log$i.csv" >>"$TMP/forensics.txt"
    fhours=$(awk -v a="$fhours" -v b="$h" 'BEGIN{print a + b}')
done
SCENES="--scene tests/scenes/crate-a-bare.ini --scene tests/scenes/crate-a-frame.ini"

median() { sort -g | awk '{v[NR]=$1} END {print (NR%2 ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2)}'; }
# once NAME COMMAND...: one run; its wall time (s) appended to $TMP/NAME.t,
# its CPU time (user + system of the process and the children it waited
# for: not mpirun's ranks) to $TMP/NAME.c.  Exit 4 (a log failed) is not
# expected here either: every log is good.
once() {
    name=$1
    shift
    a=$(date +%s.%N)
    /usr/bin/time -f "%U %S" -o "$TMP/$name.tm" "$@" >"$TMP/$name.out" 2>"$TMP/$name.err" || {
        cat "$TMP/$name.err" >&2
        exit 1
    }
    b=$(date +%s.%N)
    awk -v a="$a" -v b="$b" 'BEGIN{print b - a}' >>"$TMP/$name.t"
    awk '{print $1 + $2}' "$TMP/$name.tm" >>"$TMP/$name.c"
}
MPI="mpirun --bind-to core"
BATCH="batch $SCENES --manifest $TMP/replay.txt -q"
# The runs of every setting take turns, so that a change of the machine's
# load over the minutes falls on all of them alike.
# shellcheck disable=SC2086
for _ in $(seq "$RUNS"); do
    once r1 "$SW" $BATCH --threads 1
    once rm1 $MPI -np 1 "$SWMPI" $BATCH --threads 1
    once rm2 $MPI -np 2 "$SWMPI" $BATCH --threads 1
    once rt2 "$SW" $BATCH --threads 2
done
for k in rm1 rm2 rt2; do
    cmp "$TMP/r1.out" "$TMP/$k.out" || { echo "run-batch-bench: $k wrote other records" >&2; exit 1; }
done
# forensics of each log (batch --job forensics, one thread per rank);
# fewer runs: a run is a minute
FRUNS=$((RUNS < 3 ? RUNS : 3))
FOR="batch --job forensics --scene tests/scenes/crate-a.ini --manifest $TMP/forensics.txt -q"
# shellcheck disable=SC2086
for _ in $(seq "$FRUNS"); do
    once f1 "$SW" $FOR --threads 1
    once fm1 $MPI -np 1 "$SWMPI" $FOR --threads 1
    once fm2 $MPI -np 2 "$SWMPI" $FOR --threads 1
done
for k in fm1 fm2; do
    cmp "$TMP/f1.out" "$TMP/$k.out" || { echo "run-batch-bench: $k wrote other records" >&2; exit 1; }
done
for k in r1 rm1 rm2 rt2 f1 fm1 fm2; do
    median <"$TMP/$k.t" >"$TMP/$k.wall"
    median <"$TMP/$k.c" >"$TMP/$k.cpu"
done

row() { # LABEL NAME CORES HOURS BASE [MPI]
    awk -v l="$1" -v w="$(cat "$TMP/$2.wall")" -v c="$3" -v h="$4" -v b="$(cat "$TMP/$5.wall")" \
        -v cpu="$(cat "$TMP/$2.cpu")" -v mpi="${6:-}" \
        'BEGIN{printf "| %s | %d | %.3g | %.2f | %s | %.3g | %.0f %% |\n", l, c, h, w,
               mpi ? "-" : sprintf("%.2f", cpu), h / (c * w), 100 * b / (c * w)}'
}
{
    echo "Measured $(date -u '+%Y-%m-%d %H:%M UTC') on $(lscpu | sed -n 's/^Model name: *//p'),"
    echo "$(nproc) vCPU, $(uname -sr), $(mpirun --version | head -1), build type"
    echo "RelWithDebInfo; wall time, median of $RUNS runs ($FRUNS for forensics).  Load average at the start:"
    echo "$LOAD (a load above 1 means the machine was shared with other work)."
    echo
    echo "Replay: $(wc -l <"$TMP/replay.txt") logs of 3 to 90 minutes at 1 kHz, $hours log-hours, two"
    echo "packages (crate-a-bare.ini, crate-a-frame.ini), \`swaywatch batch\`; the records"
    echo "of every run are the same bytes.  Forensics: $(wc -l <"$TMP/forensics.txt") logs of 0.5 to 2 minutes,"
    echo "$fhours log-hours, one package (crate-a.ini) with its default what-if cases (the"
    echo "catalogue), \`swaywatch batch --job forensics\`; the records of every run are the same bytes."
    echo
    echo "| run | cores | log-hours | wall (s) | CPU (s) | log-hours per core-second | parallel efficiency |"
    echo "|---|---|---|---|---|---|---|"
    row "replay, 1 process, 1 thread" r1 1 "$hours" r1
    row "replay, \`mpirun -np 1\`" rm1 1 "$hours" r1 mpi
    row "replay, \`mpirun -np 2\` (1 thread per rank)" rm2 2 "$hours" r1 mpi
    row "replay, 1 process, 2 threads" rt2 2 "$hours" r1
    row "forensics, 1 process, 1 thread" f1 1 "$fhours" f1
    row "forensics, \`mpirun -np 1\`" fm1 1 "$fhours" f1 mpi
    row "forensics, \`mpirun -np 2\` (1 thread per rank)" fm2 2 "$fhours" f1 mpi
    echo
    awk -v h="$hours" -v c="$(cat "$TMP/r1.cpu")" -v fh="$fhours" -v fc="$(cat "$TMP/f1.cpu")" \
        'BEGIN{printf "Per CPU-second (the CPU time of the 1-core runs, which the load of other\n"
               printf "work inflates far less than the wall time): replay %.3g log-hours,\n", h / c
               printf "forensics %.3g log-hours.\n", fh / fc}'
    echo "The MPI runs' CPU time is their ranks', which \`time\` does not see through mpirun."
    echo
    echo "Load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)."
} >"$OUT"
cat "$OUT"
awk -v res="$OUT" '
    /<!-- results:begin -->/ {print; while ((getline l < res) > 0) print l; skip=1; next}
    /<!-- results:end -->/ {skip=0}
    !skip {print}' "$DOC" >"$TMP/doc" && cp "$TMP/doc" "$DOC"
echo "run-batch-bench: updated $DOC" >&2
