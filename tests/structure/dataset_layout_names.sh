#!/usr/bin/env bash
# Issue 48: a dataset's layout is named in one place, core/dataset's dataset_layout.h (and a
# captured frame's image suffixes in core's view_files.h). A string literal elsewhere in the
# sources that starts with one of those names (after an optional "/") spells the layout again and
# fails the check, listed by file and line. Names inside longer text ("a folder (manifest.csv)")
# are words, not paths, and pass.
# Usage: dataset_layout_names.sh SOURCE_DIR
set -uo pipefail
src=${1:?source folder}
cd "$src" || exit 2
header=core/dataset/include/keyturn/dataset/dataset_layout.h
[ -f "$header" ] || { echo "dataset_layout_names: no $header under $src" >&2; exit 2; }
names='manifest\.csv|dataset\.json|calibration\.json|\.keyturn|\.keyturn-lock|\.sim|snapshots|_distance\.png|_amplitude\.png|_confidence\.png'
hits=$(grep -rnE "\"/?($names)(/|\"|:)" app core rig ui drivers simulators --include='*.cpp' --include='*.h' \
  | grep -vE "^($header|core/include/keyturn/core/view_files\.h):" \
  | grep -vE '^[^:]+:[0-9]+: *//')
if [ -n "$hits" ]; then
  echo "dataset_layout_names: these spell a dataset's layout outside $header (use its names):" >&2
  echo "$hits" >&2
  exit 1
fi
echo "dataset layout: named only in $header"
