# Shared by the command-line tests: a fresh work folder, check NAME COMMAND…, skip CI_CAN WHAT,
# and the closing "N passed, N failed" line.
KT=${KEYTURN:?set KEYTURN to the keyturn binary}
work=${1:-$(mktemp -d)}
rm -rf "$work"; mkdir -p "$work"
pass=0; fail=0; skipped=0
check() {  # check NAME COMMAND...
  local name=$1; shift
  if "$@"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAILED: $name"; fi
}
# A part of the test not run here, said in one line. CI_CAN is yes when CI has the means to run it
# (scripts/install-deps.sh installs what it needs; CI runs as root): under CI=true (CI sets it) the
# skip is then a failure. After a skip and no failure, finish returns 77: ctest (SKIP_RETURN_CODE 77,
# tests/CMakeLists.txt) counts the test as skipped, not passed.
skip() {  # skip yes|no WHAT
  if [ "$1" = yes ] && [ "${CI:-}" = true ]; then
    fail=$((fail + 1)); echo "FAILED: skipped under CI=true, which has the means to run it: $2"
  else
    skipped=$((skipped + 1)); echo "SKIPPED: $2"
  fi
}
finish() {
  echo "$pass passed, $fail failed$([ "$skipped" -eq 0 ] || echo ", $skipped skipped")"
  [ "$fail" -eq 0 ] || return 1
  [ "$skipped" -eq 0 ] || return 77
}
