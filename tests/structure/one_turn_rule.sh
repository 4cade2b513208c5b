#!/usr/bin/env bash
# Issue 48: a turn's answer has one home, core/learning's TurnFusion. No other source file both
# accumulates a turn's evidence (FusionState, fuseViews) and decides an answer from it
# (Answer::Unknown / Answer::NoObject): classify --fuse, evaluate's turns and the studio feed views
# to a TurnFusion. (fusion_evaluation.cpp and nbv_evaluation.cpp fuse closed-set, with no answer.)
# Usage: one_turn_rule.sh SOURCE_DIR
set -uo pipefail
src=${1:?source folder}
cd "$src" || exit 2
[ -f core/learning/src/turn_fusion.cpp ] || { echo "one_turn_rule: no core/learning/src/turn_fusion.cpp under $src" >&2; exit 2; }
bad=0
while IFS= read -r f; do
  [ "$f" = core/learning/src/turn_fusion.cpp ] && continue
  if grep -q 'Answer::\(Unknown\|NoObject\)' "$f"; then
    echo "one_turn_rule: $f fuses views and decides a turn's answer itself (use TurnFusion, turn_fusion.h)" >&2
    bad=$((bad + 1))
  fi
done < <(grep -rlE '\bFusionState\b|\bfuseViews\(' core app ui --include='*.cpp' --include='*.h' | sort)
grep -rq 'TurnFusion' core/learning/src/model_fusion.cpp core/learning/src/live_fusion.cpp core/learning/src/open_set_evaluation.cpp \
  || { echo "one_turn_rule: a caller no longer uses TurnFusion" >&2; bad=$((bad + 1)); }
[ "$bad" -eq 0 ] && echo "one turn rule: only TurnFusion decides a turn's answer"
exit $((bad > 0))
