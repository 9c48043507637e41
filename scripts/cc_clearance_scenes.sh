#!/usr/bin/env bash
# ConcentricCircle against RRTConnect, RRT* and BIT* on random planar scenes, J-map checker, clearance objective
# (docs/concentric-circle.md, "Safe paths"): writes N scenes with `michi random-scenes` (seeds from S on: the
# default 101 keeps them apart from the tests' seeds 1-50), runs `michi bench` on each and prints one table of
# solved counts and median time and clearance ratios over the scenes.
# Usage: scripts/cc_clearance_scenes.sh [N=50] [RUNS=3] [TIME=1] [SEED=101]   (results in results/cc-clearance/)
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-50}
runs=${2:-3}
time=${3:-1}
seed=${4:-101}
out=results/cc-clearance
rm -rf "$out"
mkdir -p "$out"
build/bin/michi random-scenes --out "$out/scenes" --count "$n" --seed "$seed" >/dev/null
planners=michi::ConcentricCircle,geometric::RRTConnect,geometric::RRTstar,geometric::BITstar
for scene in "$out"/scenes/*.yaml; do
    name=$(basename "$scene" .yaml)
    build/bin/michi bench "$scene" --checker jmap --objective clearance --planners "$planners" --runs "$runs" \
        --time "$time" --out "$out/$name" >"$out/$name.log" 2>&1 || echo "$name: michi bench failed (see $out/$name.log)"
done
python3 - "$out" <<'PY'
import glob, os, sqlite3, statistics as st, sys
rows = {}
for db in sorted(glob.glob(os.path.join(sys.argv[1], "*", "*.db"))):
    c = sqlite3.connect(db)
    # a database where no run solved has no solution_clearance column
    cols = {r[1] for r in c.execute("pragma table_info(runs)")}
    clearance = "r.solution_clearance" if "solution_clearance" in cols else "NULL"
    for name, solved, t, cl in c.execute(
            "select p.name, r.solved, r.time, %s from runs r join plannerConfigs p on p.id = r.plannerid" % clearance):
        key = next(k for k in ("ConcentricCircle", "RRTConnect", "RRTstar", "BITstar") if k in name)
        rows.setdefault(db, {}).setdefault(key, []).append((solved, t, cl))
def med(runs, i):
    v = [r[i] for r in runs if r[0] and r[i] is not None]
    return st.median(v) if v else None
print("| planner | scenes solved (all runs) | median over scenes of time / RRTConnect's | median over scenes of clearance / RRTConnect's |")
print("|---|---:|---:|---:|")
for key in ("ConcentricCircle", "RRTConnect", "RRTstar", "BITstar"):
    solved = sum(1 for s in rows.values() if key in s and all(r[0] for r in s[key]))
    tr, cr = [], []
    for s in rows.values():
        if key not in s or "RRTConnect" not in s:
            continue
        tk, tc = st.median(r[1] for r in s[key]), st.median(r[1] for r in s["RRTConnect"])
        ck, cc = med(s[key], 2), med(s["RRTConnect"], 2)
        if tc > 0:
            tr.append(tk / tc)
        if ck is not None and cc:
            cr.append(ck / cc)
    print("| %s | %d / %d | %s | %s |" % (key, solved, len(rows), "%.1f" % st.median(tr) if tr else "-",
                                         "%.2f" % st.median(cr) if cr else "-"))
PY
