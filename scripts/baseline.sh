#!/usr/bin/env bash
# Runs the stock planners on every bundled problem (the baseline of docs/benchmarks.md) into results/baseline/.
# Usage: scripts/baseline.sh [--runs N]   (each problem's own time limit applies)
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${2:-10}
planners=geometric::RRTConnect,geometric::PRM,geometric::LazyPRM,geometric::KPIECE1,geometric::RRTstar,geometric::BITstar
for p in planar_2link planar_3dof_hand xarm6_ring se2_corridor se2_corridor_pgm panda_table_pick movingai_arena; do
    rm -rf "results/baseline/$p"
    build/bin/michi bench "problems/$p.yaml" --planners "$planners" --runs "$runs" --out "results/baseline/$p"
done
