#!/usr/bin/env bash
# The README's replay screenshot (docs/img/replay_panda_table_pick.png): runs the browser test in build/ (which writes
# the page of panda_table_pick with `michi plan ... --html --seed 1` and screenshots it in headless chromium) and copies
# its first screenshot. Run after scripts/build.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
ctest --test-dir build -L browser --output-on-failure
cp build/tests/viewer_browser/panda_table_pick-a.png docs/img/replay_panda_table_pick.png
echo "wrote docs/img/replay_panda_table_pick.png"
