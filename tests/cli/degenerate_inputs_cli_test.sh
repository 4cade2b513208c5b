#!/usr/bin/env bash
# Inputs that load (or parse) fine and are degenerate, and the fuzzers' findings, through the tool
# (issue 35): one line naming the file and what is wrong, exit 1; never a crash, never "unexpected
# failure". A bad manifest row is named and the rest of the dataset verified.
set -u
source "$(dirname "$0")/lib.sh"
reg=$(cd "$(dirname "$0")/../fuzz/regressions" && pwd)
one_line() { test "$(wc -l < "$1")" -eq 1; }

# The two clouds of the issue (SIGSEGV in RadiusSearch::radius before) and the chain harness's findings.
for f in chain_one_point_1000_times chain_sphere_5cm_1000km; do
  "$KT" describe -q "$reg/$f.pcd" > /dev/null 2> "$work/$f.err"
  rc=$?
  check "describe $f exits 1 (rc $rc)" test "$rc" -eq 1
  check "  names the file and the degenerate cloud" grep -q "^keyturn describe: $reg/$f.pcd: degenerate cloud: " "$work/$f.err"
  check "  (one line)" one_line "$work/$f.err"
done

# fuzz_point_cloud: a second DATA line (PCL threw std::out_of_range: "unexpected failure", exit 2).
"$KT" describe -q "$reg/pcd_second_data_line.pcd" > /dev/null 2> "$work/data.err"
rc=$?
check "a PCD with a second DATA line exits 1 (rc $rc)" test "$rc" -eq 1
check "  names the line" grep -q "pcd_second_data_line.pcd: corrupt PCD header: line 10 ('DATA') is a header line after DATA" "$work/data.err"
check "  (one line)" one_line "$work/data.err"

# A model whose sidecar lacks its feature specification, or was cut short: one line naming the file
# and what is wrong, not the JSON library's "[json.exception.out_of_range.403] …" or 120 characters
# of its text ending mid-word (issue 52).
shipped=$(cd "$(dirname "$0")/../../data/models/sim-objects" && pwd)
"$KT" render builtin:mug --angles 0 --out "$work/view.pcd" > /dev/null 2>&1
mkdir -p "$work/nospec" "$work/cut"
jq -c 'del(.feature_spec)' "$shipped/model.json" > "$work/nospec/model.json"
head -c 5000 "$shipped/model.json" > "$work/cut/model.json"
cp "$shipped/model.xgb.json" "$work/nospec/"
cp "$shipped/model.xgb.json" "$work/cut/"
"$KT" classify "$work/nospec" "$work/view.pcd" -q > /dev/null 2> "$work/nospec.err"
check "a model without feature_spec exits 1" test $? -eq 1
check "  names the file and the missing key" grep -qx "keyturn: $work/nospec/model.json: 'feature_spec' is missing" "$work/nospec.err"
check "  (one line)" one_line "$work/nospec.err"
"$KT" classify "$work/cut" "$work/view.pcd" -q > /dev/null 2> "$work/cut.err"
check "a cut model.json exits 1" test $? -eq 1
check "  names the file and where it ends, whole" \
  grep -qx "keyturn: $work/cut/model.json: not JSON at byte 5000 (.*; expected .*)" "$work/cut.err"
check "  (one line)" one_line "$work/cut.err"

# verify: a row naming a file outside the dataset and one with a name no file system holds are
# bad rows, named; the views of the other rows are verified.
"$KT" capture --class mug --instance m1 --mesh builtin:mug --step 120 -q --out "$work/ds" > /dev/null 2>&1
check "a small dataset" test -f "$work/ds/manifest.csv"
sha=$(printf '0%.0s' $(seq 64))
{
  echo "mug,m1,30,30.000,10.000,10.0000,2026-01-01T00:00:00.000Z,../../../../etc/hostname,$sha"
  echo "mug,m1,30,30.000,20.000,20.0000,2026-01-01T00:00:00.000Z,mug/$(printf 'a%.0s' $(seq 300)).pcd,$sha"
} >> "$work/ds/manifest.csv"
"$KT" verify "$work/ds" > "$work/verify.txt" 2> "$work/verify.err"
rc=$?
check "verify with bad rows exits 1 (rc $rc)" test "$rc" -eq 1
check "  nothing on stderr" test ! -s "$work/verify.err"
check "  the row outside the dataset is named" \
  grep -q "^bad manifest row: line 5: file '../../../../etc/hostname' leaves the dataset folder ('..')$" "$work/verify.txt"
check "  the over-long name is named" grep -q "^bad manifest row: line 6: file name 'mug/aaaa.*more than 255" "$work/verify.txt"
check "  the other views are verified" grep -q "3 views, 0 missing, 0 corrupt, 0 orphan, 0 duplicate files — PROBLEMS" "$work/verify.txt"
finish
