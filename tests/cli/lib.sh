# Shared by the command-line tests: a fresh work folder, check NAME COMMAND…,
# and the closing "N passed, N failed" line.
KT=${KEYTURN:?set KEYTURN to the keyturn binary}
work=${1:-$(mktemp -d)}
rm -rf "$work"; mkdir -p "$work"
pass=0; fail=0
check() {  # check NAME COMMAND...
  local name=$1; shift
  if "$@"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAILED: $name"; fi
}
finish() {
  echo "$pass passed, $fail failed"
  test "$fail" -eq 0
}
