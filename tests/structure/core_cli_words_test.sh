#!/usr/bin/env bash
# scripts/check-core-cli-words.sh on trees made here: a string literal naming a flag under core/
# fails the check and is listed by file and line; the same words in comments, outside core/ or
# without a letter after "--" pass.
# Usage: core_cli_words_test.sh WORK_DIR
set -uo pipefail
check_script="$(cd "$(dirname "$0")/../.." && pwd)/scripts/check-core-cli-words.sh"
work=${1:?work folder}
rm -rf "$work" && mkdir -p "$work/bad/core/src" "$work/bad/app" "$work/clean/core/include"
failures=0
check() {
  local what=$1
  shift
  if "$@"; then echo "ok: $what"; else echo "FAIL: $what"; failures=$((failures + 1)); fi
}

cat > "$work/bad/core/src/study.cpp" <<'CPP'
// --shard I/N is parsed in app/; comments may name flags.
/* "--eps" inside a block comment
   spanning lines */
const char dash = '-';
const long big = 1'000'000;
void f() { throw Error("shard 5 of 4: expected 1 <= shard <= shards"); }
void g() { throw Error("poses give no overlap; --force scores anyway"); }
const char* quoted = "say \"x\" then --eps 1:2:1";
const char* raw = R"x(line one
-- not a flag, then --explain)x";
const char* minus = "a -- b, x--";
CPP
echo 'const char* flag = "--bins";  // app/ may name flags' > "$work/bad/app/options.cpp"
cp "$work/bad/core/src/study.cpp" "$work/clean/core/include/study.h"
sed -i '/--force\|--eps 1\|--explain/d' "$work/clean/core/include/study.h"

bash "$check_script" "$work/bad" > "$work/bad.out" 2> "$work/bad.err"
check "a flag in a string literal under core/ fails the check" test $? -eq 1
check "it lists each literal by file and line, and only those" \
  test "$(grep '^core/' "$work/bad.err")" = "$(printf '%s\n' \
    'core/src/study.cpp:7: "poses give no overlap; --force scores anyway"' \
    'core/src/study.cpp:8: "say \"x\" then --eps 1:2:1"' \
    'core/src/study.cpp:9: "line one\n-- not a flag, then --explain"')"
check "and says how many" grep -q "^check-core-cli-words: 3 string literal(s) under core/ name a command-line flag" "$work/bad.err"

# drivers/, rig/ and simulators/ are read too; another program's command line (udevadm's) is not a flag.
mkdir -p "$work/lower/core" "$work/lower/drivers/src" "$work/lower/rig/src"
echo 'void f() { throw Error("libMesaSR not found, or use --camera sim"); }' > "$work/lower/drivers/src/lib.cpp"
echo 'const char* rule = "sudo udevadm control --reload-rules";' > "$work/lower/drivers/src/udev.cpp"
echo 'void g() { throw Error("--pose sim needs a simulated camera"); }' > "$work/lower/rig/src/rig.cpp"
bash "$check_script" "$work/lower" > /dev/null 2> "$work/lower.err"
check "a flag in drivers/ or rig/ fails the check too" test $? -eq 1
check "both listed, udevadm's command line not" \
  test "$(grep -E '^(drivers|rig)/' "$work/lower.err")" = "$(printf '%s\n' \
    'drivers/src/lib.cpp:1: "libMesaSR not found, or use --camera sim"' \
    'rig/src/rig.cpp:1: "--pose sim needs a simulated camera"')"

bash "$check_script" "$work/clean" > "$work/clean.out" 2>&1
check "comments, character literals and dashes without a letter pass" test $? -eq 0
bash "$check_script" "$work/none" > /dev/null 2>&1
check "a tree without core/ is an error, not a pass" test $? -eq 2

[ "$failures" -eq 0 ] && echo "all checks passed" || { cat "$work/bad.err"; exit 1; }
