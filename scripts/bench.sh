#!/usr/bin/env bash
# Quick start (1): set up, build, and run `michi bench` on the bundled default problem (planar_2link).
# Extra arguments go to michi bench (e.g. --runs 5 --time 1). Results: results/planar_2link/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
problem=${MICHI_PROBLEM:-problems/planar_2link.yaml}
out=results/$(basename "$problem" .yaml)
rm -rf "$out"
build/bin/michi bench "$problem" --out "$out" "$@"
