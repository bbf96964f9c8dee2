#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# No output overwrites an input or another output, on any command or path:
# the same name, a symbolic link, a hard link, './x' for 'x', a dangling
# link to where another output goes, standard input redirected from the
# log.  Each is refused with exit 2 naming both files, before anything is
# written: every file is unchanged after.
. "$(dirname "$0")/lib.sh"

SCENE_SRC=$SRC/sample_logs/crate.ini
cp "$SRC/sample_logs/hard-stop-overturn.csv" "$TMP/log.csv"
cp "$SCENE_SRC" "$TMP/s.ini"
cd "$TMP"
cp log.csv log.orig
cp s.ini s.orig
printf 'keep\n' >keep.csv
cp keep.csv keep.orig

# refused WHAT TEXT1 TEXT2 COMMAND...: exit 2, both names on stderr, no
# file changed.
refused() {
    what=$1 t1=$2 t2=$3
    shift 3
    run "$@"
    expect_rc 2 "$what"
    expect_err "$t1" "$what"
    expect_err "$t2" "$what"
    expect_prefixed_err "$what"
    cmp -s log.csv log.orig || fail "$what: the log changed"
    cmp -s s.ini s.orig || fail "$what: the scene changed"
    cmp -s keep.csv keep.orig || fail "$what: keep.csv changed"
    rm -f new.csv
}

ln -s log.csv sym.csv
ln log.csv hard.csv
ln -s s.ini sym.ini
ln -s new.csv dangling.csv

# replay, CSV path
refused "replay --out LOG" "--out log.csv: that is the log being read" "LOG log.csv" \
    "$SW" replay log.csv -s s.ini --out log.csv
refused "replay --events LOG" "--events log.csv: that is the log being read" "(LOG log.csv)" \
    "$SW" replay log.csv -s s.ini --events log.csv
refused "replay --out symlink to LOG" "--out sym.csv: that is the log being read" \
    "(LOG log.csv)" "$SW" replay log.csv -s s.ini --out sym.csv
refused "replay --out hard link to LOG" "--out hard.csv: that is the log being read" \
    "(LOG log.csv)" "$SW" replay log.csv -s s.ini --out hard.csv
refused "replay -s s.ini -o s.ini" "--out s.ini: that is a scene file being read" \
    "(--scene s.ini)" "$SW" replay log.csv -s s.ini -o s.ini
refused "replay -o symlink to the scene" "--out sym.ini: that is a scene file being read" \
    "(--scene s.ini)" "$SW" replay log.csv -s s.ini -o sym.ini
refused "replay --out X --events X" "--out keep.csv and --events keep.csv name the same file" \
    "keep.csv" "$SW" replay log.csv -s s.ini --out keep.csv --events keep.csv
refused "replay --out new --events ./new" "--out new.csv and --events ./new.csv name the same" \
    "./new.csv" "$SW" replay log.csv -s s.ini --out new.csv --events ./new.csv
refused "replay --out dangling link --events its target" \
    "--out dangling.csv and --events new.csv name the same file" "new.csv" \
    "$SW" replay log.csv -s s.ini --out dangling.csv --events new.csv
refused "replay - < LOG --out LOG" "--out log.csv: that is the log being read" \
    "(LOG - (standard input))" sh -c '"$1" replay - -s s.ini --out log.csv <log.csv' sh "$SW"

# replay, lcm-logger path (the sync word is enough to choose it)
printf '\355\241\332\001junk' >rec.lcmlog
cp rec.lcmlog rec.orig
refused "replay LCM --out LOG" "--out rec.lcmlog: that is the log being read" "LOG rec.lcmlog" \
    "$SW" replay rec.lcmlog -s s.ini --out rec.lcmlog
refused "replay LCM --events = --out" "--out keep.csv and --events keep.csv name the same" \
    "keep.csv" "$SW" replay rec.lcmlog -s s.ini --out keep.csv --events keep.csv
if "$SW" --help | grep -q monitor; then
    refused "replay --publish file://LOG" "--publish rec.lcmlog: that is the log being read" \
        "LOG rec.lcmlog" "$SW" replay rec.lcmlog -s s.ini --publish 'file://rec.lcmlog?mode=w'
    refused "monitor --lcm-url file://SCENE?mode=w" \
        "--lcm-url s.ini: that is a scene file being read" "(--scene s.ini)" \
        "$SW" monitor -s s.ini --lcm-url 'file://s.ini?mode=w'
fi
cmp -s rec.lcmlog rec.orig || fail "the lcm-logger log changed"

# simulate
refused "simulate -o SCENE" "--out s.ini: that is a scene file being read" "(--scene s.ini)" \
    "$SW" simulate -s s.ini --pulse half-sine --amplitude -9 --omega 10 -o s.ini
refused "simulate --out X --events X" "--out keep.csv and --events keep.csv" "same file" \
    "$SW" simulate -s s.ini --pulse half-sine --amplitude -9 --omega 10 --out keep.csv \
    --events keep.csv

# forensics
refused "forensics --out LOG" "--out log.csv: that is the log being read" "(LOG log.csv)" \
    "$SW" forensics log.csv -s s.ini --out log.csv --no-what-if
ln log.csv log.png
refused "forensics --plot hard link to LOG" "--plot log.png: that is the log being read" \
    "(LOG log.csv)" "$SW" forensics log.csv -s s.ini --plot log.png --no-what-if
refused "forensics --events SCENE" "--events sym.ini: that is a scene file being read" \
    "(--scene s.ini)" "$SW" forensics log.csv -s s.ini --events sym.ini --no-what-if

# boundary
refused "boundary --out SCENE" "--out s.ini: that is a scene file being read" \
    "(--scene s.ini)" "$SW" boundary -s s.ini --pulse half-sine --omega-ratio 2 --out s.ini
refused "boundary --detail X --islands X" "--detail keep.csv and --islands keep.csv" \
    "same file" "$SW" boundary -s s.ini --pulse half-sine --omega-ratio 2 --out new.csv \
    --detail keep.csv --islands keep.csv

# batch: the same rules (logs, scenes of the command line and of a
# manifest line, the manifest; --out and --csv apart)
printf '%s\n' log.csv >man.txt
cp man.txt man.orig
cp s.ini line.ini
cp s.ini line.orig
printf 'log.csv --scene line.ini\n' >man2.txt
refused "batch -o SCENE" "--out s.ini: that is a scene file being read" "(--scene s.ini)" \
    "$SW" batch log.csv -s s.ini -o s.ini
refused "batch --csv symlink to SCENE" "--csv sym.ini: that is a scene file being read" \
    "(--scene s.ini)" "$SW" batch log.csv -s s.ini -o new.jsonl --csv sym.ini
refused "batch -o a manifest line's scene" "--out line.ini: that is a scene file being read" \
    "(--scene line.ini)" "$SW" batch -s s.ini --manifest man2.txt -o line.ini
cmp -s line.ini line.orig || fail "batch: a manifest line's scene changed"
refused "batch -o LOG" "--out log.csv: that is the log being read" "(LOG log.csv)" \
    "$SW" batch log.csv -s s.ini -o log.csv
refused "batch --csv hard link to LOG" "--csv hard.csv: that is the log being read" \
    "(LOG log.csv)" "$SW" batch log.csv -s s.ini --csv hard.csv -o new.jsonl
refused "batch -o the manifest" "--out man.txt: that is the manifest being read" \
    "(--manifest man.txt)" "$SW" batch -s s.ini --manifest man.txt -o man.txt
cmp -s man.txt man.orig || fail "batch: the manifest changed"
refused "batch -o ./new --csv new" "--out ./new.csv and --csv new.csv name the same file" \
    "one would overwrite the other" "$SW" batch log.csv -s s.ini -o ./new.csv --csv new.csv
[ ! -e new.csv ] || fail "batch -o ./new --csv new: a file was written"
refused "batch -o X --csv X" "--out keep.csv and --csv keep.csv name the same file" \
    "keep.csv" "$SW" batch log.csv -s s.ini -o keep.csv --csv keep.csv
refused "batch -o dangling link --csv its target" \
    "--out dangling.csv and --csv new.csv name the same file" "new.csv" \
    "$SW" batch log.csv -s s.ini -o dangling.csv --csv new.csv
run "$SW" batch log.csv -s s.ini -o a.jsonl --csv b.csv -q
expect_rc 0 "batch with distinct outputs"
python3 -c 'import json,sys; [json.loads(l) for l in open("a.jsonl")]' ||
    fail "batch: the JSON Lines are not whole"
head -1 b.csv | grep -q '^index,line,log,' || fail "batch: the CSV table has no header"

# Different files are still fine.
run "$SW" replay log.csv -s s.ini --out a.csv --events b.csv -q
expect_rc 0 "replay with distinct outputs"
echo "ok"
