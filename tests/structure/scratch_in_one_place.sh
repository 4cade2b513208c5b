#!/usr/bin/env bash
# A test's scratch goes through tests/support/scratch_path.h (ScratchFolder: named by the test and the
# process, removed when the test leaves its scope, even after an ASSERT). No other test source builds
# a path under the temporary folder itself (temp_directory_path, a "/tmp/..." literal, mkstemp/mkdtemp,
# tmpnam, QTemporaryDir/File, QDir::tempPath, getenv("TMPDIR")): such paths were never removed, and a
# suite run left hundreds of them in /tmp. Whatever still leaks fails scratch.tmpdir_left_empty.
# The check is first run on a planted tree under WORK, where it must name the one file that breaks it.
# Usage: scratch_in_one_place.sh SOURCE_DIR WORK
set -uo pipefail
src=${1:?source folder}
work=${2:?work folder}
pattern='temp_directory_path|"/tmp/|\bmk[sd]temps?\(|\btmpnam\(|QTemporary(Dir|File)|QDir::tempPath|getenv\("TMPDIR"\)'

# The test sources under ROOT/tests that make scratch paths themselves, one a line.
offenders() {
  (cd "$1" && grep -rlE "$pattern" tests --include='*.cpp' --include='*.h' --include='*.c' --include='*.hpp' |
    grep -vx 'tests/support/scratch_path.h' | sort)
}

rm -rf "$work" && mkdir -p "$work/tests/support" "$work/tests/core" || exit 2
printf 'inline auto p() { return std::filesystem::temp_directory_path(); }\n' > "$work/tests/support/scratch_path.h"
printf 'TEST(A, B) { const ScratchFolder s("b"); }\n' > "$work/tests/core/good_test.cpp"
printf 'TEST(A, C) { auto d = std::filesystem::temp_directory_path() / "x"; }\n' > "$work/tests/core/bad_test.cpp"
planted=$(offenders "$work")
rm -rf "$work"
if [ "$planted" != tests/core/bad_test.cpp ]; then
  echo "scratch_in_one_place: on a planted tree the check named '${planted//$'\n'/, }', not tests/core/bad_test.cpp" >&2
  exit 2
fi

[ -f "$src/tests/support/scratch_path.h" ] || { echo "scratch_in_one_place: no $src/tests/support/scratch_path.h" >&2; exit 2; }
found=$(offenders "$src")
if [ -n "$found" ]; then
  echo "scratch_in_one_place: these test sources make temporary paths themselves (use keyturn::test::ScratchFolder," \
       "tests/support/scratch_path.h):" >&2
  while IFS= read -r f; do
    grep -nE "$pattern" "$src/$f" | sed "s#^#  $f:#" >&2
  done <<<"$found"
  exit 1
fi
echo "scratch in one place: $(cd "$src" && grep -rlE 'ScratchFolder' tests --include='*.cpp' --include='*.h' | wc -l) test sources use ScratchFolder, none makes a temporary path itself"
