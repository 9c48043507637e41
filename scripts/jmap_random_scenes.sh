#!/usr/bin/env bash
# The J-map check of issue 3 on random planar scenes (docs/jmap.md, "Random planar scenes"): makes COUNT scenes
# (seeds 1..COUNT) with `michi random-scenes` (the planar_2link arm among 6 random polygons), runs
# `michi jmap SCENE --verify STATES --seed 1` on each (conservative J-map checker against FCL on the same uniform
# states), prints one line per scene and a total, and exits 1 when a scene has unsafe_states > 0.
# Usage: scripts/jmap_random_scenes.sh [COUNT] [STATES]   (defaults 50 and 1000000; ~4 s per scene at 1000000)
# Results: results/jmap_random_scenes/ (scenes/scene_<seed>.yaml, jmap/scene_<seed>/jmap.json and jmap.svg).
set -euo pipefail
cd "$(dirname "$0")/.."
count=${1:-50}
states=${2:-1000000}
for v in "$count" "$states"; do
    if ! [[ $v =~ ^[1-9][0-9]*$ ]]; then
        echo "usage: scripts/jmap_random_scenes.sh [COUNT] [STATES] (positive integers; got '$v')" >&2
        exit 2
    fi
done
# build if needed: the whole project the first time (scripts/build.sh), else only the michi command
if [[ -x build/bin/michi ]]; then
    mkdir -p results
    if ! cmake --build build --target michi_cli -j"$(nproc 2>/dev/null || echo 2)" >results/jmap_random_scenes.build.log 2>&1; then
        cat results/jmap_random_scenes.build.log >&2
        exit 1
    fi
else
    bash scripts/build.sh
fi
michi=build/bin/michi
out=results/jmap_random_scenes
rm -rf "$out"
mkdir -p "$out/jmap"
"$michi" random-scenes --count "$count" --seed 1 --out "$out/scenes" >/dev/null

# one line per scene (the figures of DIR/jmap.json), then the total over every scene
summary() {
    python3 - "$@" <<'EOF'
import json, statistics, sys
mode, files = sys.argv[1], sys.argv[2:]
rows = []
for f in files:
    j = json.load(open(f))
    j["ratio"] = j["fcl_query_ns"] / j["jmap_query_ns"] if j["jmap_query_ns"] > 0 else float("inf")
    rows.append(j)
if mode == "scene":
    j = rows[0]
    print(f"{j['problem']:>9}  jmap_polygons {j['polygons']:2d}  unsafe {j['unsafe_states']}  "
          f"false_invalid {j['false_invalid_fraction']:.4f}  fcl_invalid {j['fcl_invalid_fraction']:.4f}  "
          f"jmap_ns {j['jmap_query_ns']:7.1f}  fcl_ns {j['fcl_query_ns']:7.1f}  ratio {j['ratio']:5.1f}", flush=True)
    sys.exit(0)
def spread(key):
    v = [r[key] for r in rows]
    return f"min {min(v):.4g} / median {statistics.median(v):.4g} / max {max(v):.4g}"
checked = sum(r["checked_states"] for r in rows)
unsafe = sum(r["unsafe_states"] for r in rows)
false_invalid = sum(r["false_invalid_states"] for r in rows)
print(f"total: {len(rows)} scenes, {checked} states: unsafe_states {unsafe} "
      f"({sum(r['unsafe_states'] > 0 for r in rows)} scenes with unsafe states)")
print(f"  false-invalid fraction {false_invalid / checked:.4f} of all states; per scene {spread('false_invalid_fraction')}")
print(f"  FCL-invalid fraction per scene {spread('fcl_invalid_fraction')}")
print(f"  query time fcl_query_ns / jmap_query_ns per scene {spread('ratio')}")
print(f"  jmap_query_ns {spread('jmap_query_ns')}; fcl_query_ns {spread('fcl_query_ns')}")
sys.exit(1 if unsafe > 0 else 0)
EOF
}

began=$(date +%s)
results=()
for ((seed = 1; seed <= count; ++seed)); do
    dir=$out/jmap/scene_$seed
    if ! "$michi" jmap "$out/scenes/scene_$seed.yaml" --out "$dir" --verify "$states" --seed 1 \
        >/dev/null 2>"$dir.log"; then
        echo "scene_$seed: michi jmap failed:" >&2
        cat "$dir.log" >&2
        exit 1
    fi
    summary scene "$dir/jmap.json"
    results+=("$dir/jmap.json")
done
status=0
summary total "${results[@]}" || status=$?
echo "  $((count)) scenes x $states states in $(($(date +%s) - began)) s (michi jmap, one after the other)"
if [[ $status -ne 0 ]]; then
    echo "FAILED: some scene has unsafe states (the J-map called a colliding state valid)" >&2
fi
exit $status
