#!/usr/bin/env bash
# The tests' temporary folder (TMPDIR of every ctest test, tests/CMakeLists.txt).
#   reset DIR: DIR emptied (made when missing), before any test runs (fixture setup);
#   check DIR: fails listing what is left in DIR after every test has run (fixture cleanup): a test,
#              or a program it ran, that leaves files in TMPDIR leaves them in a user's /tmp too.
# Usage: test_tmpdir.sh reset|check DIR
set -uo pipefail
mode=${1:?reset or check}
dir=${2:?the tests\' temporary folder}
case "$mode" in
  reset)
    rm -rf "$dir" && mkdir -p "$dir" || { echo "test_tmpdir: cannot empty $dir" >&2; exit 1; }
    echo "test_tmpdir: $dir is empty" ;;
  check)
    [ -d "$dir" ] || { echo "test_tmpdir: no $dir (the setup test scratch.tmpdir_reset made it)" >&2; exit 1; }
    # Qt's own runtime folder (XDG_RUNTIME_DIR when unset: TMPDIR/runtime-USER, mode 0700) is one per
    # user, made once and reused by every Qt program, as /run/user/UID would be: not a leak.
    left=$(find "$dir" -mindepth 1 -maxdepth 1 ! -name "runtime-$(id -un)" -printf '%f\n' | sort)
    if [ -z "$left" ]; then
      echo "test_tmpdir: $dir is empty: no test left a temporary file"
      exit 0
    fi
    echo "test_tmpdir: $(printf '%s\n' "$left" | wc -l) entries left in $dir by the tests (each test's scratch goes through"
    echo "  tests/support/scratch_path.h's ScratchFolder, a script's through trap 'rm -rf ...' EXIT):"
    # By family (the name up to its pid or random part), then every entry.
    printf '%s\n' "$left" | sed -E 's/[-_.][0-9]+([-_.].*)?$//; t; s/[-_.][A-Za-z0-9]{6}$//' | sort | uniq -c | sort -rn
    printf '%s\n' "$left" | sed 's/^/  /'
    exit 1 ;;
  *) echo "test_tmpdir: unknown mode $mode (reset or check)" >&2; exit 2 ;;
esac
