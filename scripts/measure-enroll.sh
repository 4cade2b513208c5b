#!/usr/bin/env bash
# keyturn enroll's figures (docs/reconstruction.md, "Enroll"; issue 50): one object added to a model
# from INPUT (a mesh file, or a keyturn reconstruct folder holding mesh.ply), timed; then
# - the object on new views rendered from its TRUE_MESH: elevations 40 and 50 degrees (between and
#   beyond the recipe's 30/45/60), every 10 degrees, another noise seed, through both simulated cameras;
# - the model's other objects before and after, on scripts/beyond-training.sh's views (the 27 objects of
#   data/objects/objects-27.csv at 30/40/45/60 degrees every 45 degrees, seed 2, both cameras; made in
#   BEYOND when absent; the old model's answers kept there too): its own objects named right, the others answered unknown.
# ENROLL_ARGS (environment) is passed to enroll (e.g. "--step 10"); NEW_ELEVATIONS (default 40,50) sets the new views' elevations. About 10 minutes on 2 cores with the
# beyond-training views already made.
# usage: scripts/measure-enroll.sh INPUT TRUE_MESH CLASS INSTANCE [MODEL] [OUT] [BEYOND]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
KT=$root/build/app/keyturn
input=$1 true_mesh=$(realpath "$2") cls=$3 instance=$4
model=${5:-$root/data/models/sim-objects}
out=${6:-out/enroll-$instance}
beyond=${7:-$out/beyond}
mkdir -p "$out" "$beyond"
rm -rf "$out/model"
# shellcheck disable=SC2086
/usr/bin/time -f "enroll: %e s wall, %U s user + %S s system CPU (load average before: $(cut -d' ' -f1 /proc/loadavg))" \
  -o "$out/time.txt" "$KT" enroll "$input" --class "$cls" --instance "$instance" --model "$model" --out "$out/model" \
  ${ENROLL_ARGS:-} 2> "$out/enroll.log"
cat "$out/time.txt"
tail -1 "$out/enroll.log"
printf 'class,instance,mesh\n%s,%s,%s\n' "$cls" "$instance" "$true_mesh" > "$out/object.csv"
for camera in sr4000 openni2; do
  "$KT" simulate --camera $camera --objects "$out/object.csv" --elevations "${NEW_ELEVATIONS:-40,50}" --step 10 --seed 2 -q \
    --out "$out/new-$camera"
  "$KT" classify "$out/model" "$out/new-$camera" --json -q > "$out/new-$camera.json"
  [ -d "$beyond/views-$camera" ] || "$KT" simulate --camera $camera --objects "$root/data/objects/objects-27.csv" \
    --elevations 30,40,45,60 --step 45 --seed 2 -q --out "$beyond/views-$camera"
  [ -s "$beyond/before-$camera.json" ] || "$KT" classify "$model" "$beyond/views-$camera" --json -q > "$beyond/before-$camera.json"
  "$KT" classify "$out/model" "$beyond/views-$camera" --json -q > "$out/after-$camera.json"
done
python3 - "$out" "$beyond" "$instance" <<'PY'
import json, sys, collections
out, beyond, new = sys.argv[1:4]
pct = lambda a, b: f"{100 * a / b:.1f} % of {b}" if b else "–"
print(f"{new}: named on its new views (true mesh, seed 2)")
print("| camera | elevation | named | unknown | another class |")
print("|---|---|---:|---:|---:|")
total = [0, 0]
for camera in ("sr4000", "openni2"):
    cells = collections.defaultdict(lambda: [0, 0, 0])
    for v in json.load(open(f"{out}/new-{camera}.json")):
        c = cells[v["view"].split("/")[-2].lstrip("e")]
        c[0] += 1; c[1] += v["class"] == new; c[2] += v["class"] == "unknown"
    for e in sorted(cells, key=float):
        n, right, unk = cells[e]
        total[0] += n; total[1] += right
        print(f"| {camera} | {e}° | {pct(right, n)} | {pct(unk, n)} | {pct(n - right - unk, n)} |")
print(f"| both | all | {pct(total[1], total[0])} | | |")
print()
print("The model's other objects on scripts/beyond-training.sh's views (30/40/45/60°, seed 2), before → after")
print("| camera | own objects named right | other objects unknown | the new object named |")
print("|---|---:|---:|---:|")
for camera in ("sr4000", "openni2"):
    before = {v["view"]: v["class"] for v in json.load(open(f"{beyond}/before-{camera}.json"))}
    after = {v["view"]: v["class"] for v in json.load(open(f"{out}/after-{camera}.json"))}
    known = None
    own = [0, 0, 0]; other = [0, 0, 0]; newv = [0, 0]
    classes_before = set(json.load(open(f"{beyond}/before-{camera}.json"))[0]["probabilities"])
    for view, a in after.items():
        instance = view.split("/")[-3]
        b = before[view]
        if instance in classes_before:
            own[0] += 1; own[1] += b == instance; own[2] += a == instance
        elif instance == new:
            newv[0] += 1; newv[1] += a == instance
        else:
            other[0] += 1; other[1] += b == "unknown"; other[2] += a == "unknown"
    print(f"| {camera} | {pct(own[1], own[0])} → {100 * own[2] / own[0]:.1f} % | "
          f"{pct(other[1], other[0])} → {100 * other[2] / other[0]:.1f} % | {pct(newv[1], newv[0])} |")
PY
