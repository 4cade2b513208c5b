#!/usr/bin/env bash
# keyturn capture as a user runs it on the simulated rig: killed with SIGKILL
# twice mid-sequence, stopped with Ctrl-C once, resumed each time; at the end
# the dataset verifies and holds every view exactly once.
set -u
KT=${KEYTURN:?set KEYTURN to the keyturn binary}
work=${1:-$(mktemp -d)}
rm -rf "$work"; mkdir -p "$work"
pass=0; fail=0
check() { local name=$1; shift; if "$@"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAILED: $name"; fi; }
ds="$work/ds"
cmd=("$KT" capture --class mug --instance builtin --step 5 --range 180 --settle 0.02 -q --out "$ds")
rows() { [ -f "$ds/manifest.csv" ] && echo $(( $(wc -l < "$ds/manifest.csv") - 1 )) || echo 0; }

for round in 1 2; do
  "${cmd[@]}" 2> "$work/kill$round.err" &
  pid=$!
  target=$((round * 8))
  for _ in $(seq 300); do [ "$(rows)" -ge "$target" ] && break; sleep 0.02; done
  kill -9 "$pid"; wait "$pid" 2>/dev/null
  check "round $round: killed mid-capture" test "$(rows)" -lt 36
done
"${cmd[@]}" 2> "$work/int.err" &
pid=$!
for _ in $(seq 300); do [ "$(rows)" -ge 24 ] && break; sleep 0.02; done
kill -INT "$pid"; wait "$pid"; rc=$?
check "Ctrl-C exits 130" test "$rc" -eq 130
check "Ctrl-C says how to resume" grep -q "run the same command again to resume" "$work/int.err"

"${cmd[@]}" 2> "$work/resume.err"
check "resume exits 0" test $? -eq 0
check "resume skipped what was there" grep -qE "already there" "$work/resume.err"
check "36 views in the manifest" test "$(rows)" -eq 36
check "every angle exactly once" test "$(tail -n +2 "$ds/manifest.csv" | cut -d, -f5 | sort -u | wc -l)" -eq 36
"$KT" verify "$ds" > "$work/verify.txt"
check "verify passes" test $? -eq 0
check "verify counts 36 views" grep -q "36 views, 0 missing, 0 corrupt, 0 orphan, 0 duplicate files — OK" "$work/verify.txt"

# Measured angles match the commanded ones (the table settled before each view).
bad=$(tail -n +2 "$ds/manifest.csv" | awk -F, '{d=$5-$6; if (d<0) d=-d; if (d>0.11 && d<359.89) print}' | wc -l)
check "measured within tolerance of commanded" test "$bad" -eq 0

# A corrupted file is found.
pcd=$(ls "$ds"/mug/builtin/e30/a45.0.pcd)
printf 'x' >> "$pcd"
"$KT" verify "$ds" > "$work/verify2.txt"
check "verify fails on a corrupt file" test $? -ne 0
check "verify names it" grep -q "^corrupt: mug/builtin/e30/a45.0.pcd" "$work/verify2.txt"
"$KT" describe "$ds" -q > "$work/features.csv"
check "describe reads the dataset" test "$(wc -l < "$work/features.csv")" -eq 37

echo "$pass passed, $fail failed"
test "$fail" -eq 0
