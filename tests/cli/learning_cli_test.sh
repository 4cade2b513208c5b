#!/usr/bin/env bash
# evaluate, train, classify, consistency and sharded describe as a user runs
# them, on a small simulated dataset: two categories with two instances each,
# two elevations, 12 views per turn (96 views).
set -u
source "$(dirname "$0")/lib.sh"

"$KT" simulate --objects "$(dirname "$0")/../data/objects-two-categories.csv" --elevations 30,60 --step 30 -q --out "$work/ds" 2> "$work/sim.err"
check "simulate exits 0" test $? -eq 0
cp -r "$work/ds" "$work/ds_sharded"
cp -r "$work/ds" "$work/ds_bare"

# A broken install (the program copied without its plugins): the run stops with one line naming the
# plugin, and caches nothing for the views. It once recorded "plugin 'pcl_io' not found" as every
# view's problem in the dataset's feature cache, and the next run, with the plugins found, read those
# rows back: 3,240 views "without keypoint features" and 8 % accuracy, exit 0.
mkdir -p "$work/bare/bin" && cp "$KT" "$work/bare/bin/keyturn"
env -u KEYTURN_PLUGIN_PATH "$work/bare/bin/keyturn" train "$work/ds_bare" --features kpd2 -q --out "$work/bare_model" \
  > /dev/null 2> "$work/bare.err"
check "a missing plugin stops train: exit 1" test $? -eq 1
check "a missing plugin: one line naming it" test "$(grep -c "^keyturn: plugin '.*' (libkeyturn_.*\.so) not found in" "$work/bare.err")" -eq 1
check "a missing plugin: nothing else said" test "$(wc -l < "$work/bare.err")" -eq 1
check "a missing plugin: no view cached as failed" test "$(cat "$work"/ds_bare/.keyturn/features-*.csv 2> /dev/null | grep -c 'not found in')" -eq 0
"$KT" train "$work/ds_bare" --features kpd2 -q --out "$work/bare_model" 2> "$work/bare2.err"
check "with the plugins found, every view is described" \
  test "$(grep -v '^#' "$work"/ds_bare/.keyturn/features-*.csv | awk -F, 'NR > 1 && $5 < 0' | wc -l)" -eq 0

fast="--rounds 10 --epochs 15"
"$KT" evaluate "$work/ds" --features "kpd2 kpd2+gkpd2 esf" --classifier xgboost,mlp \
  --protocol kfold4,leave-elevation,leave-instance $fast -q --out "$work/report" --json > "$work/report.json"
check "evaluate exits 0" test $? -eq 0
for f in report.md report.csv report.json confusion/kfold4_32bins.png confusion/leave-elevation_32bins.png \
         confusion/leave-instance_32bins.png pdfs/kpd2_ycb_006_mustard_bottle.png; do
  check "report has $f" test -s "$work/report/$f"
done
# 3 feature sets × 2 classifiers × 3 protocols.
check "one CSV row per set, classifier and protocol" test "$(tail -n +2 "$work/report/report.csv" | wc -l)" -eq 18
check "fold counts: 4, 2 elevations, 4 instances" \
  test "$(awk -F, 'NR > 1 {print $2 ":" $6}' "$work/report/report.csv" | sort -u | tr '\n' ' ')" = \
       "kfold4:4 leave-elevation:2 leave-instance:4 "
check "every test view tested once per row" test "$(awk -F, 'NR > 1 && $7 != 96' "$work/report/report.csv" | wc -l)" -eq 0
check "accuracies are fractions" test "$(awk -F, 'NR > 1 && ($8 < 0 || $8 > 1)' "$work/report/report.csv" | wc -l)" -eq 0
# Four instances: chance is 25 %. Keypoint distances on the same views must do far better.
acc=$(awk -F, '$2 == "kfold4" && $4 == "kpd2+gkpd2" && $5 == "xgboost" {print $8}' "$work/report/report.csv")
check "kpd2+gkpd2 beats chance under k-fold ($acc)" awk -v a="$acc" 'BEGIN {exit !(a > 0.6)}'
check "leave-instance labels categories" grep -q '"label": "category"' "$work/report.json"
# The same evaluation as array jobs: two parts, then --merge. Every number of the report is the
# single run's; the wall times (JSON seconds, train_ms_per_view, predict_ms_per_view) are not compared.
for i in 1 2; do
  "$KT" evaluate "$work/ds" --features "kpd2 kpd2+gkpd2 esf" --classifier xgboost,mlp \
    --protocol kfold4,leave-elevation,leave-instance $fast -q --out "$work/sharded" --shard $i/2
done
check "two evaluation parts" test -s "$work/sharded/parts/part-1-of-2.json" -a -s "$work/sharded/parts/part-2-of-2.json"
check "a part is no report" test ! -e "$work/sharded/report.json"
"$KT" evaluate "$work/ds" --features "kpd2 kpd2+gkpd2 esf" --classifier xgboost,mlp \
  --protocol kfold4,leave-elevation,leave-instance $fast -q --out "$work/sharded" --merge --json > "$work/merged.json"
check "evaluate --merge exits 0" test $? -eq 0
numbers='del(.seconds) | .rows[] |= del(.train_ms_per_view, .predict_ms_per_view)'
check "the merged report's numbers are the single run's" \
  test "$(jq -S "$numbers" "$work/report.json")" = "$(jq -S "$numbers" "$work/merged.json")"
check "the merged CSV is the single run's but for the times" \
  test "$(cut -d, -f1-9 "$work/report/report.csv")" = "$(cut -d, -f1-9 "$work/sharded/report.csv")"
check "the merged confusion plots are the single run's" cmp -s "$work/report/confusion/kfold4_32bins.png" \
  "$work/sharded/confusion/kfold4_32bins.png"
"$KT" evaluate "$work/ds" --features kpd2 --classifier xgboost --protocol kfold4 $fast -q --out "$work/sharded" --merge \
  2> "$work/foreign.err"
check "parts of another plan are refused" grep -q "part-1-of-2.json: made by another evaluation (differs in classifiers, feature_sets" "$work/foreign.err"
"$KT" evaluate "$work/ds" --out "$work/sharded" --shard 3/2 -q 2> "$work/shard.err"
check "a shard outside 1..N is named" grep -q -- "--shard 3/2: expected I/N with 1 <= I <= N" "$work/shard.err"

cache=$(ls "$work"/ds/.keyturn/features-*.csv)
check "one feature cache" test "$(echo "$cache" | wc -l)" -eq 1
before=$(stat -c %Y "$cache")
sleep 1
"$KT" evaluate "$work/ds" --features kpd2 --classifier xgboost --protocol kfold4 $fast -q --out "$work/report2"
check "a second evaluate reuses the cache" test "$(stat -c %Y "$cache")" -eq "$before"
check "the same split gives the same accuracy" test \
  "$(awk -F, '$2 == "kfold4" && $4 == "kpd2" && $5 == "xgboost" {print $8}' "$work/report/report.csv")" = \
  "$(awk -F, '$2 == "kfold4" {print $8}' "$work/report2/report.csv")"

# Shards of an array job merge into the same cache.
"$KT" describe "$work/ds_sharded" --shard 1/2 -q && "$KT" describe "$work/ds_sharded" --shard 2/2 -q
check "two shards written" test "$(ls "$work"/ds_sharded/.keyturn/*shard-*-of-2.csv | wc -l)" -eq 2
"$KT" evaluate "$work/ds_sharded" --features kpd2 --classifier xgboost --protocol kfold4 $fast --out "$work/report3" \
  2> "$work/merge.err"
check "evaluate merges the shards" grep -q "merged 2 feature shards" "$work/merge.err"
check "merged cache equals the single-process one" cmp -s "$cache" "$work/ds_sharded/.keyturn/$(basename "$cache")"

# A model: train, classify views, refuse features computed another way.
"$KT" train "$work/ds" --features kpd2+gkpd2 --classifier xgboost $fast -q --out "$work/model"
check "train writes the sidecar and the weights" test -s "$work/model/model.json" -a -s "$work/model/model.xgb.json"
"$KT" classify "$work/model" "$work/ds/can/ycb_005_tomato_soup_can/e30/a0.0.pcd" \
  "$work/ds/bottle/ycb_006_mustard_bottle/e60/a90.0.pcd" --json -q > "$work/classify.json"
check "classify exits 0" test $? -eq 0
check "classify names both views" test "$(grep -c '"view"' "$work/classify.json")" -eq 2
check "a training view is classified as itself" \
  grep -A1 -E '"class": "ycb_005_tomato_soup_can"' "$work/classify.json" -q
"$KT" classify "$work/model" "$cache" -q > "$work/classify_cache.txt"
check "classify a feature cache: one line per view" test "$(wc -l < "$work/classify_cache.txt")" -eq 96
# classify describes a view with the model's own parameters, computing only its blocks:
# the same class and probability as the model gives the view's row in the cache.
"$KT" classify "$work/model" "$work/ds/bottle/ycb_006_mustard_bottle/e60/a90.0.pcd" -q > "$work/classify_one.txt"
check "a view and its cached row classify alike" test \
  "$(cut -f2,3 "$work/classify_one.txt")" = \
  "$(grep '^bottle/ycb_006_mustard_bottle/e60/a90.0	' "$work/classify_cache.txt" | cut -f2,3)"
"$KT" classify "$work/model" "$work/ds/can/ycb_005_tomato_soup_can/e30/a0.0.pcd" --bins 16 -q 2> "$work/flags.err"
check "classify takes no feature flags (the model has them)" grep -q "bins" "$work/flags.err"
sed 's/^# bins=32$/# bins=16/' "$cache" > "$work/bins16.csv"
"$KT" classify "$work/model" "$work/bins16.csv" -q 2> "$work/mismatch.err"
check "features with other bins are refused" test $? -ne 0
check "the mismatch names the parameter" grep -q "bins: model 32, features 16" "$work/mismatch.err"

# The set network over the keypoints: trained, saved, and a view classified from its file as from its
# cached row; features that are not the keypoints, and a nearest-reference open set over them, are one line.
"$KT" train "$work/ds" --features kpset --classifier setnet --set-epochs 20 -q --out "$work/setnet"
check "train --classifier setnet writes the sidecar and the network" \
  test "$(jq -r '.classifier + " " + .weights + " " + (.inputs | tostring)' "$work/setnet/model.json")" = "setnet model.pt 193"
"$KT" classify "$work/setnet" "$cache" -q > "$work/setnet_cache.txt"
"$KT" classify "$work/setnet" "$work/ds/bottle/ycb_006_mustard_bottle/e60/a90.0.pcd" -q > "$work/setnet_one.txt"
check "the set network: a view and its cached row classify alike" test \
  "$(cut -f2,3 "$work/setnet_one.txt")" = \
  "$(grep '^bottle/ycb_006_mustard_bottle/e60/a90.0	' "$work/setnet_cache.txt" | cut -f2,3)"
check "the set network names most of its 96 training views (chance 1 in 4)" \
  test "$(awk -F'\t' '{split($1, p, "/"); if (p[2] == $2) n++} END {print n + 0}' "$work/setnet_cache.txt")" -ge 72
"$KT" train "$work/ds" --features kpd2 --classifier setnet -q --out "$work/setnet_pdf" 2> "$work/setnet_pdf.err"
check "setnet on PDFs: exit 1" test $? -eq 1
check "setnet on PDFs: one line" test "$(cat "$work/setnet_pdf.err")" = \
  "keyturn: set network: 32 feature columns; it needs the keypoints first (features 'kpset' or 'kpset+…', 193 values)"
"$KT" train "$work/ds" --features kpset --classifier setnet --label category --open-set knn-relative -q \
  --out "$work/setnet_knn" 2> "$work/setnet_knn.err"
check "a nearest-reference open set over the keypoints: one line" grep -q \
  "^keyturn: open-set method 'knn-relative' measures distances between feature rows, and block 'kpset' lists keypoints in no fixed order: use the max-probability method$" \
  "$work/setnet_knn.err"

"$KT" consistency "$work/ds" --object can/ycb_002_master_chef_can --out "$work/cons" -q
check "consistency writes CSV and one plot per elevation" test -s "$work/cons/consistency.csv" -a -s "$work/cons/consistency_e30.png" -a -s "$work/cons/consistency_e60.png"
check "the first view is identical to itself" \
  test "$(awk -F, '$1 == 30 && $2 == 0 {print $4 + $8}' "$work/cons/consistency.csv")" = "0"
check "24 views + header" test "$(wc -l < "$work/cons/consistency.csv")" -eq 25
# A training-side twin: the same views each with its own camera, trained on only beside its view.
"$KT" simulate --objects "$(dirname "$0")/../data/objects-two-categories.csv" --elevations 30,60 --step 30 -q \
  --jitter-distance 0.15 --jitter-elevation 5 --jitter-tilt 3 --jitter-scale 0.2 --jitter-integration 15:60 --out "$work/twin"
check "a jittered simulate exits 0" test $? -eq 0
check "the twin has the same view ids" \
  test "$(cut -d, -f1-3,5 "$work/twin/manifest.csv" | sort)" = "$(cut -d, -f1-3,5 "$work/ds/manifest.csv" | sort)"
check "its views are seen from their own elevations" \
  test "$(awk -F, 'NR > 1 && $4 != $3' "$work/twin/manifest.csv" | wc -l)" -gt 80
"$KT" evaluate "$work/ds" --train-extra "$work/twin" --features kpd2 --classifier xgboost --protocol leave-instance \
  $fast -q --out "$work/augmented" --json > "$work/augmented.json"
check "evaluate --train-extra exits 0" test $? -eq 0
check "the report says what trained beside the views" grep -q "Training augmented by 96 twin views" "$work/augmented/report.md"
check "every fold's training views brought their twins" \
  test "$(grep -c '"twin_views"' "$work/augmented.json")" -eq 4
"$KT" simulate --objects "$(dirname "$0")/../data/objects-two-categories.csv" --elevations 30 --step 45 -q --out "$work/other"
"$KT" evaluate "$work/ds" --train-extra "$work/other" --features kpd2 --classifier xgboost --protocol kfold4 \
  $fast -q --out "$work/r5" 2> "$work/extra.err"
check "a twin of other views is refused" test $? -ne 0
check "the refusal names the twin and the view" grep -q "other: view .*/e30/a45.0 is not a view of the dataset" "$work/extra.err"
"$KT" evaluate "$work/ds" --protocol sideways --out "$work/r4" 2> "$work/proto.err"
check "an unknown protocol is named" grep -q "unknown protocol 'sideways'" "$work/proto.err"
finish
