#!/usr/bin/env bash
# Kill-and-resume stress of keyturn capture on the simulated rig, under CPU load: each round
# captures a 36-view sequence into a fresh dataset, killing the capture at random moments
# (SIGKILL, or SIGINT as Ctrl-C) and resuming it until it completes, then verifies. After every
# kill the dataset is checked as a resume would find it. Prints what it found by kind:
#   tmp     leftover temporary files (NAME.tmp.XXXXXX, NAME.tmp, NAME.tmp.png) after a kill / at the end
#   corrupt a file whose SHA-256 differs from its manifest row; missing: a row's file absent
#   dup     a view with two rows; failed: rounds whose final verify is not OK
# usage: KEYTURN=path/to/keyturn kill_stress.sh WORKDIR [ROUNDS] [LOAD_WORKERS] [SEED] [KILLS]
set -u
source "$(dirname "$0")/../cli/lib.sh"
rounds=${2:-20}
load=${3:-2}
RANDOM=${4:-1}
kills=${5:-4}

busy=()
for _ in $(seq 1 "$load"); do ( while :; do :; done ) & busy+=($!); done
stop_load() { for p in "${busy[@]}"; do kill "$p" 2> /dev/null; done; }
trap stop_load EXIT

is_tmp='\.tmp(\.[A-Za-z0-9]{6})?(\.[a-z]+)?$'
count_tmp() { find "$1" -path "$1/.sim" -prune -o -type f -print | grep -cE "$is_tmp" || true; }
rows() { [ -f "$1/manifest.csv" ] && echo $(( $(wc -l < "$1/manifest.csv") - 1 )) || echo 0; }

sigkills=0; sigints=0; tmp_after_kill=0; bad_after_kill=0
tmp_end=0; corrupt_end=0; missing_end=0; dup_end=0; failed=0
for r in $(seq 1 "$rounds"); do
  ds="$work/r$r"
  # KILLS runs killed 1-3 views in, at a random moment 0-0.4 s after a row (a view takes ~0.3 s,
  # a quarter of it writing its files, so about one kill in five lands in the writes); then one
  # run to the end.
  for k in $(seq 0 "$kills"); do
    "$KT" capture --class mug --instance builtin --step 5 --range 180 --settle 0.01 -q --out "$ds" \
        2>> "$work/r$r.err" > /dev/null &
    pid=$!
    if [ "$k" -lt "$kills" ]; then
      target=$(( $(rows "$ds") + 1 + RANDOM % 3 ))
      for _ in $(seq 1500); do [ "$(rows "$ds")" -ge "$target" ] || ! kill -0 "$pid" 2> /dev/null && break; sleep 0.01; done
      sleep "0.$(printf %03d $((RANDOM % 400)))"
      if kill -0 "$pid" 2> /dev/null; then
        if [ $((RANDOM % 3)) -eq 0 ]; then sig=INT; sigints=$((sigints + 1)); else sig=KILL; sigkills=$((sigkills + 1)); fi
        kill -s "$sig" "$pid" 2> /dev/null; wait "$pid" 2> /dev/null
        # What a resume finds: leftovers, and rows whose files are not whole (those must never be).
        t=$(count_tmp "$ds"); [ "$t" -gt 0 ] && tmp_after_kill=$((tmp_after_kill + 1))
        if [ -f "$ds/manifest.csv" ]; then
          "$KT" verify "$ds" > "$work/r$r.kill.txt" 2> /dev/null
          grep -qE '^(corrupt|missing|duplicate): ' "$work/r$r.kill.txt" && { bad_after_kill=$((bad_after_kill + 1)); cp "$work/r$r.kill.txt" "$work/r$r.bad-after-kill.txt"; }
        fi
        continue
      fi
    fi
    wait "$pid"; rc=$?
    [ "$rc" -eq 0 ] || echo "round $r: capture exited $rc (see $work/r$r.err)"
    break
  done
  "$KT" verify "$ds" > "$work/r$r.verify.txt" 2> /dev/null; vrc=$?
  t=$(count_tmp "$ds"); [ "$t" -gt 0 ] && tmp_end=$((tmp_end + 1))
  grep -q '^corrupt: ' "$work/r$r.verify.txt" && corrupt_end=$((corrupt_end + 1))
  grep -q '^missing: ' "$work/r$r.verify.txt" && missing_end=$((missing_end + 1))
  grep -q '^duplicate: ' "$work/r$r.verify.txt" && dup_end=$((dup_end + 1))
  [ "$(rows "$ds")" -ne 36 ] && dup_end=$((dup_end + 1))
  if [ "$vrc" -ne 0 ]; then failed=$((failed + 1)); echo "round $r: $(tail -1 "$work/r$r.verify.txt")"; fi
done

echo "rounds                          $rounds (load: $load busy loops)"
echo "kills                           $sigkills SIGKILL, $sigints SIGINT"
echo "kills leaving temporaries       $tmp_after_kill"
echo "kills leaving a bad row         $bad_after_kill (corrupt/missing/duplicate right after the kill)"
echo "rounds ending with temporaries  $tmp_end"
echo "rounds ending corrupt/missing   $corrupt_end / $missing_end"
echo "rounds ending not 36 rows once  $dup_end"
echo "rounds failing verify           $failed"
check "captures were killed" test "$((sigkills + sigints))" -gt 0
check "no round fails verify" test "$failed" -eq 0
check "no kill leaves a row whose files are not whole" test "$bad_after_kill" -eq 0
check "no round ends with temporaries" test "$tmp_end" -eq 0
finish
