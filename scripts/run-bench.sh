#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Regenerate docs/accuracy-speed.md's measured part, docs/img/pareto.png and
# its data in bench/results/: build with the benchmarks, run sw_bench (one
# plane against two included), time CSV replay of an hour-long 1 kHz log
# (and ten hours, for peak memory), count instructions with callgrind,
# record the machine.
#   scripts/run-bench.sh           full run (about half an hour on 2 vCPU)
#   QUICK=1 scripts/run-bench.sh   a smoke run (shorter workloads, 1 run)
# Uses gnuplot; times the swaywatch replay command as well when it exists.
set -eu
cd "$(dirname "$0")/.."
BUILD=${BUILD:-build}
RUNS=${RUNS:-5}
DOC=docs/accuracy-speed.md
cmake -S . -B "$BUILD" -DSW_WERROR=ON -DSW_BUILD_BENCH=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$BUILD" -j 2 --target sw_bench
B="$BUILD/bench/sw_bench"
TMP=$(mktemp -d /tmp/sw-bench.XXXXXX)
trap 'rm -rf "$TMP"' EXIT
OUT="$TMP/results.md"
DATA=bench/results   # recorded with the document: the plot's data
mkdir -p "$DATA"

{
    echo "Measured $(date -u '+%Y-%m-%d %H:%M UTC') on $(lscpu | sed -n 's/^Model name: *//p'),"
    echo "$(nproc) vCPU, $(uname -sr), $(cc --version | head -1), build type RelWithDebInfo (-O2)."
    echo "Load average at the start: $(cut -d' ' -f1-3 /proc/loadavg)"
    echo "(a load above 1 means the machine was shared with other work while measuring)."
    echo
} >"$OUT"

if [ -n "${QUICK:-}" ]; then
    "$B" run --quick --runs 1 --data "$DATA" >>"$OUT"
    HOURS=0.1
else
    "$B" run --runs "$RUNS" --data "$DATA" >>"$OUT"
    HOURS=1
fi

# ---- one plane against two (issue 29) ----------------------------------------
{
    echo "### One plane against two (shocks workload, sw_bench planes)"
    echo
    echo "CPU ns per sample of the engine (the input's own cost subtracted), median"
    echo "of $RUNS runs, the three interleaved; the second plane is the first's twin."
    echo
    if [ -n "${QUICK:-}" ]; then "$B" planes --runs 1 --seconds 20; else "$B" planes --runs "$RUNS"; fi
    echo
} >>"$OUT"

# ---- CSV replay: parse + engine, end to end --------------------------------
median() { sort -g | awk '{v[NR]=$1} END {print (NR%2 ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2)}'; }
"$B" gen-csv --hours "$HOURS" >"$TMP/road.csv"
rows=$(($(wc -l <"$TMP/road.csv") - 1))
{
    echo "### CSV replay of the road log ($rows rows, $(du -m "$TMP/road.csv" | cut -f1) MB)"
    echo
    echo "From the first byte read to the last sample integrated, CSV parsing"
    echo "included; median of $RUNS runs.  CPU time of the process (what the"
    echo "software costs) and wall time (what it took on the shared machine);"
    echo "ns per row from the CPU time.  'max RSS' is the process's peak resident"
    echo "memory; the 10x row streams ten times the log through a pipe (its wall"
    echo "time is the generator's)."
    echo
    echo "| path | model | rows | CPU (s) | wall (s) | ns per row | max RSS (KiB) |"
    echo "|---|---|---|---|---|---|---|"
} >>"$OUT"
field() { sed -n "s/.* $1 \([0-9.]*\).*/\1/p" "$TMP/r"; }
for m in bare frame; do
    : >"$TMP/t"
    : >"$TMP/w"
    for _ in $(seq "$RUNS"); do
        "$B" replay-csv "$TMP/road.csv" --model "$m" >"$TMP/r"
        field cpu >>"$TMP/t"
        field wall >>"$TMP/w"
    done
    c=$(median <"$TMP/t")
    w=$(median <"$TMP/w")
    rss=$(field max_rss_kib)
    echo "| library (sw_csv + engine, file) | $m | $rows | $c | $w | $(awk -v c="$c" -v n="$rows" 'BEGIN{printf "%.0f", 1e9*c/n}') | $rss |" >>"$OUT"
    for k in 1 10; do
        h=$(awk -v h="$HOURS" -v k="$k" 'BEGIN{print h*k}')
        "$B" gen-csv --hours "$h" | "$B" replay-csv - --model "$m" >"$TMP/r"
        n=$(field rows)
        c=$(field cpu)
        echo "| library, ${k}x log through a pipe | $m | $n | $c | - | $(awk -v c="$c" -v n="$n" 'BEGIN{printf "%.0f", 1e9*c/n}') | $(field max_rss_kib) |" >>"$OUT"
    done
done
SW="$BUILD/swaywatch"
if cmake --build "$BUILD" -j 2 --target swaywatch-cli >/dev/null 2>&1 && "$SW" replay --help >/dev/null 2>&1; then
    # the defaults (the reserve at 10 Hz of sample time included), and
    # the replay alone (--reserve-rate 0)
    for rr in default 0; do
        for m in bare frame; do
            : >"$TMP/t"
            for _ in $(seq "$RUNS"); do
                # shellcheck disable=SC2046
                /usr/bin/time -f "%U %S %e %M" -o "$TMP/tm" "$SW" replay "$TMP/road.csv" \
                    --scene "tests/scenes/crate-a-$m.ini" \
                    $([ "$rr" = 0 ] && echo --reserve-rate 0) >/dev/null
                cat "$TMP/tm" >>"$TMP/t"
            done
            c=$(awk '{print $1 + $2}' "$TMP/t" | median)
            w=$(cut -d' ' -f3 "$TMP/t" | median)
            rss=$(cut -d' ' -f4 "$TMP/t" | sort -n | tail -1)
            what="\`swaywatch replay\` (whole process)"
            [ "$rr" = 0 ] && what="\`swaywatch replay --reserve-rate 0\`"
            echo "| $what | $m | $rows | $c | $w | $(awk -v c="$c" -v n="$rows" 'BEGIN{printf "%.0f", 1e9*c/n}') | $rss |" >>"$OUT"
        done
    done
else
    echo "| \`swaywatch replay\` | - | - | not built in this tree | | | |" >>"$OUT"
fi
echo >>"$OUT"

# ---- instruction counts (callgrind): noise-free, per sample -------------------
if command -v valgrind >/dev/null 2>&1; then
    # instructions of one workload per input sample: difference of 25 s and 5 s
    ipc() {
        a=$(valgrind --tool=callgrind --callgrind-out-file=/dev/null "$B" "$@" --seconds 5 2>&1 |
            sed -n 's/.*refs: *//p' | tr -d ,)
        b=$(valgrind --tool=callgrind --callgrind-out-file=/dev/null "$B" "$@" --seconds 25 2>&1 |
            sed -n 's/.*refs: *//p' | tr -d ,)
        echo $(((b - a) / 20000))
    }
    gen=$(ipc gen)
    {
        echo "### Instructions per input sample (callgrind)"
        echo
        echo "Counted, not timed: the same on a busy or an idle machine.  Road rows have"
        echo "the cost of generating the log ($gen per sample) subtracted."
        echo
        echo "| workload | model | instructions per sample |"
        echo "|---|---|---|"
        for m in bare frame; do
            echo "| rocking, rk4 dt 1e-3 (one step per sample) | $m | $(ipc rock --model $m --dt 1e-3) |"
            echo "| rocking, rk4 dt 1e-4 (ten steps per sample) | $m | $(ipc rock --model $m --dt 1e-4) |"
            echo "| road, default (rk4 dt 1e-3) | $m | $(($(ipc road --model $m) - gen)) |"
            [ "$m" = frame ] &&
                echo "| road, rk4 dt 1e-3, stuck frame stepped | $m | $(($(ipc road --model $m --stepped) - gen)) |"
            echo "| road, GSL driver baseline | $m | $(($(ipc baseline --model $m) - gen)) |"
        done
        # one plane against two: the input's own cost subtracted
        for m in bare frame cushion-soft; do
            in=$(ipc shocks --model $m --planes 0)
            one=$(($(ipc shocks --model $m --planes 1) - in))
            two=$(($(ipc shocks --model $m --planes 2) - in))
            echo "| shocks (input subtracted), one plane / two planes (ratio) | $m | $one / $two ($(awk -v a="$one" -v b="$two" 'BEGIN{printf "%.3f", b/a}')) |"
        done
        echo
    } >>"$OUT"
fi
echo "Load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)." >>"$OUT"

# ---- plot --------------------------------------------------------------------
models=""
for f in "$DATA"/pareto-*.dat; do
    m=$(basename "$f" .dat)
    m=${m#pareto-}
    models="$models $m"
    # Pareto front: settings sorted by cost, keeping each that beats every cheaper one
    grep -v '^#' "$f" | sort -k4,4g |
        awk 'BEGIN{best=2} $5<best {best=$5; print $4, $5}' >"$DATA/front-$m.dat"
done
gnuplot -e "dir='$DATA'; out='docs/img/pareto.png'; models='${models# }'" bench/pareto.gp

# ---- splice into the document -------------------------------------------------
awk -v res="$OUT" '
    /<!-- results:begin -->/ {print; while ((getline l < res) > 0) print l; skip=1; next}
    /<!-- results:end -->/ {skip=0}
    !skip {print}' "$DOC" >"$TMP/doc" && cp "$TMP/doc" "$DOC"
scripts/accuracy-rows.sh # the rows in use, from src/lib/core/accuracy.c
echo "run-bench: updated $DOC and docs/img/pareto.png" >&2
