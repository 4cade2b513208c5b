#!/usr/bin/env bash
# No two C/C++ source files of the project share a name (issue 48: three pairs did, and a newcomer
# could not tell core's plot specs from ui's drawing, or app's cache front from learning's):
# fails listing each name found twice, with its paths. Test data and build folders aside.
# Usage: unique_source_names.sh ROOT
set -euo pipefail
root=${1:?root}
cd "$root"
dupes=$(git ls-files -- '*.cpp' '*.h' '*.c' ':!:tests/data/**' ':!:tests/fuzz/corpus/**' |
  awk -F/ '{print $NF "\t" $0}' | sort | awk -F'\t' '
    { n[$1]++; where[$1] = where[$1] " " $2 }
    END { for (f in n) if (n[f] > 1) print f ":" where[f] }' | sort)
if [ -n "$dupes" ]; then
  echo "unique_source_names: these source file names appear more than once:" >&2
  echo "$dupes" >&2
  exit 1
fi
echo "unique_source_names: every source file name is used once"
