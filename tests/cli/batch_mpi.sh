# SPDX-License-Identifier: GPL-3.0-or-later
# batch_mpi.sh - batch and boundary under mpirun: on 2 and 3 ranks, the
# same bytes as one process writes (records, CSV table, curves, detail,
# islands), every log run once and the work shared; a bad log is a record,
# not the end of the job; a manifest on standard input reaches every rank;
# a bad scene stops every rank with one message.
#   sh batch_mpi.sh SWAYWATCH SOURCE_DIR MPIEXEC NUMPROC_FLAG [MPIEXEC_FLAGS...]
# (CTest gives it the MPI that CMake found: only in a build with MPI.)
. "$(dirname "$0")/lib.sh"
MPIEXEC=$3
NP=$4
shift 4
FLAGS="$*" # words without blanks (--oversubscribe --allow-run-as-root)
# Open MPI in a container as root, on one machine: shared memory only,
# without the single-copy mechanism (it needs ptrace rights a container
# may not give).  Other MPIs ignore these.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none
# mpi N ARGS...: swaywatch ARGS on N ranks
mpi() {
    n=$1
    shift
    # shellcheck disable=SC2086
    run timeout 240 "$MPIEXEC" $FLAGS "$NP" "$n" "$SW" "$@"
}
CRATE=$SRC/sample_logs/crate.ini
FRAME=$SRC/sample_logs/crate-on-frame.ini
B=$TMP/b
python3 "$SRC/tests/cli/mkbatch.py" "$B" "$SRC/sample_logs"
M=$B/manifest.txt

# One process (this binary, not under mpirun: it never starts MPI).
run "$SW" batch --scene "$CRATE" --scene "$FRAME" --manifest "$M" -o "$TMP/one.jsonl" \
    --csv "$TMP/one.csv" --threads 2
expect_rc 4 "one process"
[ "$(wc -l <"$TMP/one.jsonl")" -eq 33 ] || fail "one process: $(wc -l <"$TMP/one.jsonl") records"

for n in 2 3; do
    mpi $n batch --scene "$CRATE" --scene "$FRAME" \
        --manifest "$M" -o "$TMP/m$n.jsonl" --csv "$TMP/m$n.csv" --threads 1
    expect_rc 4 "$n ranks: some logs failed"
    cmp "$TMP/one.jsonl" "$TMP/m$n.jsonl" || fail "$n ranks: records differ from one process"
    cmp "$TMP/one.csv" "$TMP/m$n.csv" || fail "$n ranks: CSV differs from one process"
    expect_err "batch: 20 logs: 14 done, 6 failed; 33 records" "$n ranks: the summary"
    # the messages of a failing log once, from rank 0
    [ "$(grep -c 'b/missing.csv: cannot open' "$TMP/err")" -eq 1 ] ||
        { show; fail "$n ranks: a log's message not once"; }
    # every log run once, by more than one rank
    line=$(grep "batch: $n ranks (rank 0 with 1 thread); logs run by each:" "$TMP/err") ||
        { show; fail "$n ranks: how the work was shared"; }
    sum=0 busy=0
    for c in $(echo "$line" | sed 's/.*each://'); do
        sum=$((sum + c))
        [ "$c" -gt 0 ] && busy=$((busy + 1))
    done
    [ "$sum" -eq 20 ] || fail "$n ranks ran $sum logs, not 20: $line"
    [ "$busy" -ge 2 ] || fail "$n ranks: one rank ran every log: $line"
done

# Records on standard output, the manifest on standard input (which
# mpirun gives rank 0 only).
# shellcheck disable=SC2086
run timeout 240 "$MPIEXEC" $FLAGS "$NP" 2 "$SW" batch --scene "$CRATE" --scene "$FRAME" \
    --manifest - -q <"$M"
expect_rc 4 "2 ranks, manifest on standard input"
cmp "$TMP/out" "$TMP/one.jsonl" || fail "2 ranks: standard output differs from one process"

# A scene that cannot be read: one message, exit 3 on every rank.
mpi 3 batch --scene "$TMP/none.ini" "$B/a01.csv"
expect_rc 3 "3 ranks, a missing scene"
[ "$(grep -c 'none.ini: cannot open' "$TMP/err")" -eq 1 ] ||
    { show; fail "3 ranks: the scene's message not once"; }

# boundary: one sweep, its three files, as one process writes them.
BARE=$SRC/docs/scenes/paper-bare.ini
PFRAME=$SRC/docs/scenes/paper-frame.ini
sweep() { # PREFIX RANKS (0: one process)
    p=$1
    if [ "$2" -eq 0 ]; then set -- "$SW"; else set -- timeout 240 "$MPIEXEC" $FLAGS "$NP" "$2" "$SW"; fi
    run "$@" boundary --scene "$BARE" --scene "$PFRAME" --bearing-ratio 1,1/3 --pulse full-sine \
        --omega-ratio 1:7:1.5 --max-amplitude 12 --out "$TMP/$p-c.csv" --detail "$TMP/$p-d.csv" \
        --islands "$TMP/$p-i.csv" --no-progress
    expect_rc 0 "boundary $p"
}
sweep one 0
for n in 2 3; do
    sweep m$n $n
    for f in c d i; do
        cmp "$TMP/one-$f.csv" "$TMP/m$n-$f.csv" || fail "boundary on $n ranks: $f differs"
    done
    [ "$(grep -c 'wrote .*m'$n'-c.csv' "$TMP/err")" -eq 1 ] ||
        { show; fail "boundary on $n ranks: not said once"; }
done
exit 0
