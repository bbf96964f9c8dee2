# SPDX-License-Identifier: GPL-3.0-or-later
# exports.sh - the logger and app exports of tests/data/exports read as
# tests/data/exports/expected.tsv says: for each row, replay the file with
# the row's options and compare the exit code, the columns line and a
# text of stderr (the preamble skipped, or a refusal naming its option).
# Every export has a row (the timing-*.csv files also have their own test,
# tests/cli/timing_exports.sh, about their times alone).
. "$(dirname "$0")/lib.sh"
DIR=$SRC/tests/data/exports
TABLE=$DIR/expected.tsv
SCENE=$SRC/sample_logs/crate.ini
TAB=$(printf '\t')

[ -f "$TABLE" ] || fail "no $TABLE"
rows=0
while IFS="$TAB" read -r file opts rc columns text extra; do
    case $file in '' | '#'*) continue ;; esac
    if [ -z "$text" ] || [ -n "$extra" ]; then
        fail "expected.tsv: the row of '$file' has not 5 fields"
    fi
    [ -f "$DIR/$file" ] || fail "expected.tsv: no export '$file'"
    [ "$opts" = - ] && opts=
    what="$file${opts:+ $opts}"
    # shellcheck disable=SC2086
    run "$SW" replay "$DIR/$file" --scene "$SCENE" $opts
    expect_rc "$rc" "$what"
    prefix="swaywatch: $DIR/$file: "
    got=$(awk -v p="$prefix" 'index($0, p) == 1 && index(substr($0, length(p) + 1), "time: ") == 1 {
        print substr($0, length(p) + 1) }' "$TMP/err")
    if [ "$columns" = - ]; then
        [ -z "$got" ] || { show; fail "$what: a columns line where none was expected: $got"; }
    else
        [ "$got" = "$columns" ] || {
            show
            fail "$what: columns
  got:      $got
  expected: $columns"
        }
    fi
    [ "$text" = - ] || expect_err "$text" "$what"
    expect_prefixed_err "$what"
    rows=$((rows + 1))
done <"$TABLE"
[ "$rows" -ge 16 ] || fail "expected.tsv has $rows rows"

# every export has a row
for f in "$DIR"/*.csv; do
    name=$(basename "$f")
    cut -f1 "$TABLE" | grep -qxF "$name" || fail "$name has no row in expected.tsv"
done
echo "ok: $rows rows"
