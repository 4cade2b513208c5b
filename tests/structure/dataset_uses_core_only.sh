#!/usr/bin/env bash
# core/dataset (keyturn_dataset) uses core only (docs/architecture.md): no file of it includes a
# device, the simulator, rig, learning, the studio, Qt or a device library, and its CMakeLists
# links none of their targets. Learning builds on the dataset, never the reverse.
# Usage: dataset_uses_core_only.sh SOURCE_DIR
set -euo pipefail
dir=$1/core/dataset
[[ -f $dir/CMakeLists.txt ]] || { echo "FAIL: $dir/CMakeLists.txt not found"; exit 1; }
status=0
if found=$(grep -rnE '#include *[<"](keyturn/(drivers|rig|sim|learning|bench|studio|ui)/|Q[A-Z][A-Za-z]*[>.]|libusb|modbus|embree)' "$dir") &&
   [[ -n $found ]]; then
  echo "FAIL: core/dataset includes what it may not use:"
  sed "s#^$1/#  #" <<<"$found"
  status=1
fi
if found=$(grep -nE 'keyturn_(drivers|rig|sim|learning|bench|studio_ui|ui)\b|Qt5|PkgConfig::|embree' "$dir/CMakeLists.txt" |
           grep -v '^[0-9]*:#') && [[ -n $found ]]; then
  echo "FAIL: core/dataset/CMakeLists.txt links what it may not use:"
  sed 's/^/  /' <<<"$found"
  status=1
fi
[[ $status == 0 ]] && echo "OK: core/dataset ($(find "$dir" -name '*.cpp' -o -name '*.h' | wc -l) files) uses core only"
exit $status
