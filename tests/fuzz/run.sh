#!/usr/bin/env bash
# Short, reproducible fuzz runs (fixed seed and run count) of every loader of
# outside data, from the committed seed corpus. A crash leaves its input in
# $OUT/crash-* and fails the run: turn it into a regression test.
# usage: tests/fuzz/run.sh BUILD_DIR [RUNS]
set -u
build=$(cd "${1:?hardening build folder}" && pwd)
runs=${2:-4000}
here=$(cd "$(dirname "$0")" && pwd)
out=$(mktemp -d)
pass=0; fail=0
for target in point_cloud mesh dataset configs learning; do
  bin="$build/tests/fuzz/fuzz_$target"
  corpus="$out/$target"
  mkdir -p "$corpus"
  cp "$here/corpus/$target"/* "$corpus/"
  if (cd "$out" && "$bin" -seed=1 -runs="$runs" -max_len=16384 -rss_limit_mb=2048 -timeout=20 \
        -artifact_prefix="$out/$target-" "$corpus" > "$out/$target.log" 2>&1); then
    pass=$((pass + 1))
    echo "fuzz_$target: $(grep -oE 'cov: [0-9]+' "$out/$target.log" | tail -1), $runs runs, no crash"
  else
    fail=$((fail + 1))
    echo "FAILED: fuzz_$target (log and crash input in $out):"
    grep -E 'ERROR|SUMMARY|crash-|Test unit written' "$out/$target.log" | head -8
  fi
done
echo "$pass passed, $fail failed"
test "$fail" -eq 0
