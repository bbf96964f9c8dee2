#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Evidence that a refactor keeps behaviour: writes the state and event CSVs
# and the JSON summaries of every sample log and scene (every scheme on the
# rigid models, the cushion on its own schemes), simulate pulses, a boundary
# sweep and forensics into OUTDIR, plus instructions per sample counted by
# callgrind (bench/sw_bench).  Run it before and after, then
#     diff -r BEFORE/out AFTER/out && diff BEFORE/ipc.txt AFTER/ipc.txt
#
#   scripts/refactor-check.sh OUTDIR          (BUILD=build-check by default)
#   NO_IPC=1 scripts/refactor-check.sh OUTDIR  outputs only (no valgrind)
set -eu
cd "$(dirname "$0")/.."
[ $# -eq 1 ] || { echo "usage: scripts/refactor-check.sh OUTDIR" >&2; exit 2; }
OUT=$1
BUILD=${BUILD:-build-check}
cmake -S . -B "$BUILD" -DSW_BUILD_BENCH=ON -DSW_BUILD_TESTS=OFF >/dev/null
cmake --build "$BUILD" -j 2 >/dev/null
SW="$BUILD/swaywatch"
rm -rf "$OUT"
mkdir -p "$OUT/out" "$OUT/scenes"
O="$OUT/out"

# The scenes: the samples', the tests', and the cushion on the bed.
cp sample_logs/crate.ini sample_logs/crate-on-frame.ini tests/scenes/crate-a.ini "$OUT/scenes/"
cat >"$OUT/scenes/cushion-bed.ini" <<'EOF'
[package]
name = crate-on-cushion
height = 2.0
width = 0.728
mass = 1000
[cushion]
omega = 40
zeta = 0.05
cubic = 1e7
EOF
S="$OUT/scenes"
rigid="crate crate-on-frame"
cushion="crate-a cushion-bed"

run() { # name, then the command's arguments; keeps stdout, stderr and the exit code
    name=$1
    shift
    rc=0
    "$SW" "$@" >"$O/$name.stdout" 2>"$O/$name.stderr" || rc=$?
    echo "$rc" >"$O/$name.rc"
    # A misspelt or retired option would compare equal before and after
    # (the same usage error twice) and guard nothing: stop instead.
    if grep -q "unknown option" "$O/$name.stderr"; then
        echo "refactor-check: $name: $(cat "$O/$name.stderr")" >&2
        exit 2
    fi
}
logopts() {
    case $1 in
    *g-ms*) echo "--delimiter ; --time-unit ms --accel-unit g" ;;
    *) echo "" ;;
    esac
}
for log in sample_logs/*.csv; do
    l=$(basename "$log" .csv)
    for sc in $rigid; do
        for scheme in rk4 heun euler rkf45 rkck rk8pd rk4imp bsimp msbdf; do
            n="replay-$l-$sc-$scheme"
            # shellcheck disable=SC2046
            run "$n" replay "$log" $(logopts "$log") --scene "$S/$sc.ini" --scheme "$scheme" \
                --out "$O/$n.states.csv" --events "$O/$n.events.csv" --json
        done
    done
    for sc in $cushion; do
        for scheme in default rk4 rkck rk8pd; do
            n="replay-$l-$sc-$scheme"
            sch=""
            [ "$scheme" = default ] || sch="--scheme $scheme"
            # shellcheck disable=SC2046,SC2086
            run "$n" replay "$log" $(logopts "$log") --scene "$S/$sc.ini" $sch \
                --out "$O/$n.states.csv" --events "$O/$n.events.csv" --json
        done
    done
    # all packages at once, the human summary
    # shellcheck disable=SC2046
    run "replay-$l-all" replay "$log" $(logopts "$log") --scene "$S/crate.ini" \
        --scene "$S/crate-on-frame.ini" --scene "$S/crate-a.ini" --scene "$S/cushion-bed.ini" -v
done
run replay-accuracy replay sample_logs/braking-pothole.csv --scene "$S/crate.ini" \
    --scene "$S/crate-on-frame.ini" --accuracy 1e-6 --json
for sc in crate crate-on-frame crate-a cushion-bed; do
    for p in "half-sine -5 4" "half-sine -12 9" "full-sine -6 3" "full-sine 9 12"; do
        set -- $p
        n="simulate-$sc-$1$2-$3"
        run "$n" simulate --scene "$S/$sc.ini" --pulse "$1" --amplitude "$2" --omega "$3" \
            --out "$O/$n.states.csv" --events "$O/$n.events.csv" --json
    done
done
run boundary-rigid boundary --scene "$S/crate.ini" --scene "$S/crate-on-frame.ini" \
    --pulse half-sine --omega-ratio 1:6:1 --out "$O/boundary-rigid.csv"
run boundary-cushion boundary --scene "$S/cushion-bed.ini" --pulse full-sine \
    --omega-ratio 2:6:2 --out "$O/boundary-cushion.csv"
run forensics-hard-stop forensics sample_logs/hard-stop-overturn.csv --scene "$S/crate.ini" \
    --frame-omega 8 --cushion-omega 30 --threads 1
run forensics-frame forensics sample_logs/braking-pothole.csv --scene "$S/crate-on-frame.ini" \
    --threads 1 --json
# The build's commit (forensics names the program that wrote it) differs
# at every commit by design: written as COMMIT, so that the rest compares.
for f in "$O"/*; do
    sed -i -E 's/(commit |"commit": ")[0-9a-f]{40}/\1COMMIT/g; s/"modified": (true|false)/"modified": "M"/g; s/,? with local changes//g' "$f"
done
echo "refactor-check: $(ls "$O" | wc -l) files in $O" >&2

[ -n "${NO_IPC:-}" ] && exit 0
command -v valgrind >/dev/null || { echo "refactor-check: no valgrind, no counts" >&2; exit 0; }
B="$BUILD/bench/sw_bench"
ipc() { # instructions per sample of a workload: difference of 25 s and 5 s
    a=$(valgrind --tool=callgrind --callgrind-out-file=/dev/null "$B" "$@" --seconds 5 2>&1 |
        sed -n 's/.*refs: *//p' | tr -d ,)
    b=$(valgrind --tool=callgrind --callgrind-out-file=/dev/null "$B" "$@" --seconds 25 2>&1 |
        sed -n 's/.*refs: *//p' | tr -d ,)
    echo $(((b - a) / 20000))
}
{
    gen=$(ipc gen)
    echo "gen $gen"
    for m in bare frame; do
        echo "rock $m rk4 1e-3 $(ipc rock --model $m --dt 1e-3)"
        echo "rock $m rk4 1e-4 $(ipc rock --model $m --dt 1e-4)"
        echo "road $m $(($(ipc road --model $m) - gen))"
    done
    echo "rock cushion-soft rk4 1e-3 $(ipc rock --model cushion-soft --dt 1e-3)"
    echo "rock cushion-stiff rkck $(ipc rock --model cushion-stiff --scheme rkck)"
} >"$OUT/ipc.txt"
cat "$OUT/ipc.txt"
