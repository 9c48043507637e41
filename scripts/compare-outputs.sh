#!/usr/bin/env bash
# compare-outputs.sh BEFORE_MICHI AFTER_MICHI OUTDIR [PROBLEMS_DIR]
#
# Runs two `michi` binaries (e.g. before and after a refactoring) on every bundled problem with every sub-command
# that applies to it, with fixed seeds and deterministic settings, and compares what they print and write (paths,
# JSON, SVG, PNG, Markdown, OMPL benchmark logs, the Planner Arena database) once timing fields are normalised.
# Prints one line per case, `same` or `differs` (with the first differing file and line), and the totals; the exit
# status is 0 when every case is the same, 1 otherwise. ONLY=REGEX (environment) runs only the cases whose name
# matches REGEX.
#
# Both binaries read the SAME problem files: PROBLEMS_DIR (default: the problems/ folder of the checkout holding
# this script) is copied once to OUTDIR/problems, and each binary runs in its own folder OUTDIR/before or
# OUTDIR/after, where `problems` is a link to that copy. Every path on the command line is relative
# (problems/x.yaml, out/CASE), so a path printed or written by a binary is the same string on both sides.
#
# OUTDIR/{before,after}/out/CASE/ hold the raw outputs (stdout, stderr, exit plus the files the command wrote),
# OUTDIR/norm/{before,after}/CASE/ the normalised copies that are compared, OUTDIR/results.txt the report.
#
# Determinism: plan and bench use geometric::RRTConnect (stops at its first solution) and michi's planners
# (ConcentricCircle, HeadingLattice, DualRoadmap, PathSeed); every command that takes --seed gets one; bench runs 2
# runs per planner. Time limits are generous so that no solve is cut off by the clock. Cases known to differ between
# two runs of one binary are listed in `varies` below with the reason; docs/layout-comparison.md explains the result.
#
# Command-line syntax: every case below is written in the syntax both binaries accept (`--opt value`, options after
# the problem file): CLI11 (issue 12 part 3) still takes the syntax of the hand-written parsers it replaced.
set -u -o pipefail

if [[ $# -lt 3 || $# -gt 4 ]]; then
    echo "usage: $0 BEFORE_MICHI AFTER_MICHI OUTDIR [PROBLEMS_DIR]" >&2
    exit 2
fi
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
before_bin="$(readlink -f "$1")"
after_bin="$(readlink -f "$2")"
outdir="$3"
problems="${4:-$here/../problems}"
for b in "$before_bin" "$after_bin"; do
    [[ -x "$b" ]] || { echo "$0: not an executable: $b" >&2; exit 2; }
done
[[ -d "$problems" ]] || { echo "$0: no problems folder: $problems" >&2; exit 2; }
if [[ -e "$outdir" ]]; then
    echo "$0: $outdir exists; give a new folder" >&2
    exit 2
fi
mkdir -p "$outdir"
outdir="$(cd "$outdir" && pwd)"
cp -r "$problems" "$outdir/problems"
for side in before after; do
    mkdir -p "$outdir/$side/out"
    ln -s ../problems "$outdir/$side/problems"
done
# one time limit per solve, large enough for every deterministic planner here to finish by itself
PLAN_TIME=20
# a command that runs longer than this is stopped (and shows up as a difference if only one side is stopped)
CASE_TIMEOUT=300

# ---------------------------------------------------------------------------------------------------------------
# The cases: NAME|ARGUMENTS (ARGUMENTS are split on spaces; OUT stands for out/NAME, the case's own output folder)
cases=()
add() { cases+=("$1|$2"); }
# cases whose outputs differ between two runs of ONE binary (checked by running a binary against itself), and why;
# a difference there is reported as such, not as a change between the binaries
declare -A varies=()

add list-planners "list-planners"

all_problems=()
for f in "$outdir"/problems/*.yaml; do
    all_problems+=("$(basename "$f" .yaml)")
done

# plan: every problem with RRTConnect (stops at its first solution); the problem's own seed made explicit
for p in "${all_problems[@]}"; do
    add "plan-rrtconnect-$p" "plan problems/$p.yaml --planner geometric::RRTConnect --seed 1 --time $PLAN_TIME --out OUT"
done
# plan with michi's deterministic planners where they apply (ConcentricCircle: planar/3-D arms of paper 000;
# HeadingLattice: SE(2) maps of paper 003)
for p in planar_2link arch_3dof planar_3dof_hand; do
    add "plan-circle-$p" "plan problems/$p.yaml --planner michi::ConcentricCircle --seed 1 --time $PLAN_TIME --out OUT"
done
for p in se2_corridor se2_corridor_pgm se2_rooms movingai_arena; do
    add "plan-lattice-$p" "plan problems/$p.yaml --planner michi::HeadingLattice --seed 1 --time $PLAN_TIME --out OUT"
done
# plan with the experience planner (paper 001, with the problem's library where it names one) and the dual roadmap
# (paper 002) on a static scene
for p in xarm6_ring xarm6_ring_tool; do
    add "plan-pathseed-$p" "plan problems/$p.yaml --planner michi::PathSeed --seed 1 --time $PLAN_TIME --out OUT"
done
for p in dynamic_mobile_passage dynamic_reach_box; do
    add "plan-dualroadmap-$p" "plan problems/$p.yaml --planner michi::DualRoadmap --seed 1 --time $PLAN_TIME --out OUT"
done
# plan with the J-map checker (paper 000's pre-filter) on the arms it is built for
for p in planar_2link arch_3dof planar_3dof_hand; do
    add "plan-jmap-$p" "plan problems/$p.yaml --planner geometric::RRTConnect --checker jmap --seed 1 --time $PLAN_TIME --out OUT"
done
# plan, second query of a multi-query problem
add "plan-query1-se2_rooms" "plan problems/se2_rooms.yaml --planner geometric::RRTConnect --query 1 --seed 1 --time $PLAN_TIME --out OUT"

# bench: every problem, RRTConnect, 2 runs (the benchmark seeds ompl::RNG with the problem's benchmark.seed)
for p in "${all_problems[@]}"; do
    add "bench-$p" "bench problems/$p.yaml --planners geometric::RRTConnect --runs 2 --time $PLAN_TIME --out OUT"
done
add "bench-circle-planar_2link" "bench problems/planar_2link.yaml --planners michi::ConcentricCircle,geometric::RRTConnect --runs 2 --time $PLAN_TIME --out OUT"
add "bench-lattice-se2_corridor" "bench problems/se2_corridor.yaml --planners michi::HeadingLattice,geometric::RRTConnect --runs 2 --time $PLAN_TIME --out OUT"
add "bench-checkers-planar_2link" "bench problems/planar_2link.yaml --planners geometric::RRTConnect --checker fcl,jmap --runs 2 --time $PLAN_TIME --out OUT"
add "bench-jmap-planar_3dof_hand" "bench problems/planar_3dof_hand.yaml --planners michi::ConcentricCircle,geometric::RRTConnect --checker jmap --runs 2 --time $PLAN_TIME --out OUT"
# PathSeed learns the training queries first (RRTConnect solves them), then runs held-out queries
for p in xarm6_ring xarm6_ring_tool; do
    add "bench-pathseed-$p" "bench problems/$p.yaml --planners michi::PathSeed --runs 2 --time $PLAN_TIME --out OUT"
done
# on the changed robot the recalled seed needs repair, which PathSeed (race = 1) races against RRT-Connect from
# scratch in a second thread: which thread wins, and how many motions the other checked first, is up to the scheduler
varies["bench-pathseed-xarm6_ring_tool"]="PathSeed races repair against RRT-Connect in two threads"
add "bench-query0-xarm6_ring" "bench problems/xarm6_ring.yaml --planners geometric::RRTConnect --query 0 --runs 2 --time $PLAN_TIME --out OUT"

# circles (paper 000): the arm problems
for p in planar_2link arch_3dof planar_3dof_hand; do
    add "circles-$p" "circles problems/$p.yaml --out OUT --time $PLAN_TIME"
done
add "circles-jmap-planar_2link" "circles problems/planar_2link.yaml --checker jmap --out OUT --time $PLAN_TIME"

# jmap (paper 000): the planar and 3-joint arm problems, with a seeded FCL verification (xarm6_ring left out: its
# 6-joint J-map did not finish within CASE_TIMEOUT on this machine)
for p in planar_2link arch_3dof planar_3dof_hand; do
    add "jmap-$p" "jmap problems/$p.yaml --out OUT --verify 500 --seed 1"
done

# lattice (paper 003): the SE(2) map problems
for p in se2_corridor se2_corridor_pgm se2_rooms movingai_arena; do
    add "lattice-$p" "lattice problems/$p.yaml --out OUT --time 60"
done
add "lattice-settings-se2_corridor" "lattice problems/se2_corridor.yaml --out OUT --cell-sizes 0.25,0.5 --angle-steps 0.3927,0.7854 --time 60"

# dualarm (paper 004)
add "dualarm-dual_arm" "dualarm problems/dual_arm.yaml --out OUT --seed 1 --time 1"

# replan (paper 002): the two dynamic problems, 2 episodes of the methods that repeat from run to run: the PRM and
# LazyPRM baselines grow their roadmaps against the wall clock (two runs of one binary gave different replan counts
# on dynamic_mobile_passage), so they are left out
for p in dynamic_mobile_passage dynamic_reach_box; do
    add "replan-$p" "replan problems/$p.yaml --out OUT --episodes 2 --seed 1 --methods dual,rrtconnect,dual-no-learning"
done

# experience (paper 001)
for p in xarm6_ring xarm6_ring_tool; do
    add "experience-queries-$p" "experience-queries problems/$p.yaml --out OUT/queries.yaml --count 8 --training 4 --seed 1"
done
add "path-seed-figure-xarm6_ring" "path-seed-figure problems/xarm6_ring.yaml --out OUT/figure.svg --training 0 --held-out 0 --seed 1"
add "path-seed-figure-rotation-xarm6_ring" "path-seed-figure problems/xarm6_ring.yaml --out OUT/figure.svg --training 1 --held-out 2 --variant rotation --seed 1"
add "path-seed-library-xarm6_ring" "path-seed-library problems/xarm6_ring.yaml --out OUT/library.seeds --seed 1"

# random-scenes: the default arm (problems/planar_2link.yaml, relative to the working folder) and another arm
add "random-scenes-planar_2link" "random-scenes --count 3 --seed 1 --out OUT"
add "random-scenes-planar_3dof_hand" "random-scenes --arm problems/planar_3dof_hand.yaml --count 3 --seed 5 --polygons 4 --out OUT"

# the command-line conventions themselves (issue 12 part 3 changed them on purpose: CLI11 help, one-line usage errors
# naming the command, exit 2): expected to differ, listed to show how
add "cli-help" "--help"
add "cli-unknown-option" "plan problems/planar_2link.yaml --planner geometric::RRTConnect --no-such-option 1"
add "cli-missing-out" "bench problems/planar_2link.yaml"

# ---------------------------------------------------------------------------------------------------------------
# Normalisation: what differs between two runs of the SAME binary is removed before the comparison. Each rule is
# listed in normalise.py below with the reason; nothing else is touched.
cat >"$outdir/normalise.py" <<'PY'
"""normalise.py SRC DST RUN_FOLDER: copy the outputs of one case with the run-to-run noise taken out.

Every rule says what it takes out and why; values are replaced by <T> (a measured time or rate), <HOST>, <DATE>,
<ADDR> or <RUN>, so the line itself is still compared. Found by running the same binary twice (same/same runs).
"""
import os
import re
import shutil
import sqlite3
import sys

NUM = r"-?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:e[-+]?[0-9]+)?"
# a field, JSON key, table column or OMPL run property that holds a measured duration, rate or memory use
# (michi replan's latencies are wall-clock measurements, and so are the ratios between them)
TIMING_NAME = re.compile(r"(^|[ _(])(time|times|seconds|ns|ms|us|memory|totaltime|latency)($|[ _)])|\(s\)|per second",
                         re.I)
# names that contain "time" but are settings or simulated-clock values, identical in every run: kept
KEPT_NAMES = re.compile(r"^(timelimit|planning_time|episode_time|time_limit|training_time|real_time)$", re.I)


def timing_name(name):
    name = name.strip().strip('"')
    return bool(TIMING_NAME.search(name)) and not KEPT_NAMES.match(name)


LINE_RULES = [
    # 1. OMPL benchmark log and database: the host, the start date, the total wall time of the experiment
    (re.compile(r"^Running on .*$"), "Running on <HOST>"),
    (re.compile(r"^Starting at .*$"), "Starting at <DATE>"),
    (re.compile(r"^" + NUM + r" seconds spent to collect the data$"), "<T> seconds spent to collect the data"),
    # 2. OMPL's state-space report: sampler speed (samples per second) and the goal's heap address
    (re.compile(r"(samples drawn per second: .*)"), "samples drawn per second: <T>"),
    (re.compile(r"memory address = 0x[0-9a-f]+"), "memory address = <ADDR>"),
    # 3. JSON "key": number where the key names a duration (build_seconds, jmap_query_ns, total_seconds, ...)
    (re.compile(r'("(\w+)"\s*:\s*)(' + NUM + r")"),
     lambda m: m.group(1) + ("<T>" if timing_name(m.group(2)) else m.group(3))),
    # 4. measured durations in progress and report text: "solved in 0.0214 s", "in 0.157694 seconds",
    #    "(3.00731 s)", "build 0.177934 s" (a number with a fraction directly followed by a time unit; whole
    #    numbers such as "20 seconds per run" or "(1 s each)" are settings and are kept)
    (re.compile(r"(?<![\w.])-?[0-9]*\.[0-9]+(?:e[-+]?[0-9]+)?( ?)(s|seconds|sec|ms|us|ns)\b"), r"<T>\1\2"),
]


def normalise_lines(lines, run_dir):
    out = []
    in_cpu_block = False
    run_columns = []  # the per-run property names of the OMPL benchmark log, in the order of the run rows
    md_columns = None  # the header cells of the current Markdown table
    collecting = 0  # property names still to read after "N properties for each run"
    progress_names = False  # run_columns are the progress properties
    for line in lines:
        # 0. absolute output paths (michi bench prints them): the run folder differs by construction
        line = line.replace(run_dir, "<RUN>")
        # 1b. OMPL benchmark log: the lscpu block (host hardware) between <<<| and |>>>
        if line.startswith("Architecture:"):
            in_cpu_block = True
        if in_cpu_block:
            if line.startswith("|>>>"):
                in_cpu_block = False
                out.append(line)
            continue
        # 5. OMPL benchmark log run rows: "v1; v2; ...;" in the order of the "N properties for each run" list;
        #    the time, memory and simplification time columns are measured
        m = re.match(r"^(\d+) (progress )?properties for each run$", line)
        if m:
            run_columns = []
            progress_names = bool(m.group(2))
            out.append(line)
            collecting = int(m.group(1))
            continue
        if collecting > 0:
            run_columns.append(re.sub(r" (REAL|INTEGER|BOOLEAN|ENUM|VARCHAR.*)$", "", line))
            collecting -= 1
            out.append(line)
            continue
        # 5b. progress rows "v1,v2,;v1,v2,;..." (OMPL samples the progress properties every 0.05 s while a run
        #     lasts, so the number of samples is a duration): the time column is masked and repeated samples
        #     are kept once
        if run_columns and progress_names and re.match(r"^([^;]*,;)+$", line):
            samples = []
            for token in line.split(";")[:-1]:
                values = token.split(",")[:-1]
                values = ["<T>" if timing_name(n) else v for n, v in zip(run_columns, values)]
                sample = ",".join(values) + ",;"
                if not samples or samples[-1] != sample:
                    samples.append(sample)
            out.append("".join(samples))
            continue
        if run_columns and line.rstrip().endswith(";") and line.count(";") == len(run_columns):
            cells = [c.strip() for c in line.split(";")[:-1]]
            cells = ["<T>" if timing_name(n) else c for n, c in zip(run_columns, cells)]
            out.append("; ".join(cells) + "; ")
            continue
        # 6. Markdown tables (summary.md, lattice.md, stdout): cells under a header that names a duration
        #    ("median time (s)", "build (s)", "query 0 search (s)")
        if line.startswith("|"):
            cells = line.strip().strip("|").split("|")
            if md_columns is None:
                md_columns = [c.strip() for c in cells]
            elif not all(set(c.strip()) <= set("-:") for c in cells) and len(cells) == len(md_columns):
                cells = [" <T> " if timing_name(n) else c for n, c in zip(md_columns, cells)]
                line = "|" + "|".join(cells) + "|"
        else:
            md_columns = None
        for pattern, repl in LINE_RULES:
            line = pattern.sub(repl, line)
        out.append(line)
    return out


def normalise_text(text, run_dir):
    return "\n".join(normalise_lines(text.splitlines(), run_dir)) + "\n"


# 7. the Planner Arena database: every table dumped as sorted text rows; columns that hold the host, the date,
#    the CPU or a measured duration/memory are replaced, text cells (the setup report) get the line rules
DB_MASKED = re.compile(r"^(totaltime|hostname|cpuinfo|date|time|memory|simplification_time)$", re.I)


def dump_db(path, run_dir):
    con = sqlite3.connect(path)
    lines = []
    tables = [r[0] for r in con.execute("SELECT name FROM sqlite_master WHERE type='table' ORDER BY name")]
    for t in tables:
        cols = [r[1] for r in con.execute(f'PRAGMA table_info("{t}")')]
        lines.append(f"TABLE {t}: {', '.join(cols)}")
        rows = []
        for row in con.execute(f'SELECT * FROM "{t}"'):
            cells = []
            for c, v in zip(cols, row):
                if DB_MASKED.match(c):
                    v = "<T>"
                elif isinstance(v, str):
                    v = " / ".join(normalise_lines(v.splitlines(), run_dir))
                cells.append(f"{c}={v}")
            rows.append(" | ".join(cells))
        # the progress table has one row per 0.05 s sample: with the time masked, repeated rows are kept once
        lines.extend(sorted(set(rows)) if t == "progress" else sorted(rows))
    con.close()
    return "\n".join(lines) + "\n"


src, dst, run_dir = sys.argv[1], sys.argv[2], sys.argv[3]
for root, _, files in os.walk(src):
    for f in files:
        s = os.path.join(root, f)
        d = os.path.join(dst, os.path.relpath(s, src))
        os.makedirs(os.path.dirname(d), exist_ok=True)
        if f.endswith(".db"):
            with open(d + ".txt", "w") as o:
                o.write(dump_db(s, run_dir))
        elif f.endswith(".png"):
            shutil.copyfile(s, d)  # pictures rendered from the SVG: compared byte for byte
        else:
            with open(s, encoding="utf-8", errors="replace") as i:
                text = i.read()
            with open(d, "w") as o:
                o.write(normalise_text(text, run_dir))
PY

# ---------------------------------------------------------------------------------------------------------------
run_case() {  # SIDE BIN NAME ARGS
    local side=$1 bin=$2 name=$3 args=$4
    local dir="$outdir/$side/out/$name"
    mkdir -p "$dir"
    local -a argv
    read -r -a argv <<<"${args//OUT/out/$name}"
    local t0 t1
    t0=$(date +%s.%N)
    (cd "$outdir/$side" && timeout "$CASE_TIMEOUT" "$bin" "${argv[@]}" >"out/$name/stdout" 2>"out/$name/stderr")
    echo $? >"$dir/exit"
    t1=$(date +%s.%N)
    echo "$side $name $(echo "$t1 - $t0" | bc)" >>"$outdir/durations.txt"
}

first_difference() {  # DIR_A DIR_B: "file: line N: 'a' vs 'b'" for the first differing file
    python3 - "$1" "$2" <<'PY'
import filecmp, os, sys
a, b = sys.argv[1], sys.argv[2]
def files(d):
    return sorted(os.path.relpath(os.path.join(r, f), d) for r, _, fs in os.walk(d) for f in fs)
fa, fb = files(a), files(b)
if fa != fb:
    only_a = sorted(set(fa) - set(fb)); only_b = sorted(set(fb) - set(fa))
    print(f"files: only before {only_a[:3]}, only after {only_b[:3]}")
    sys.exit()
for f in fa:
    pa, pb = os.path.join(a, f), os.path.join(b, f)
    if filecmp.cmp(pa, pb, shallow=False):
        continue
    try:
        la = open(pa).read().splitlines(); lb = open(pb).read().splitlines()
    except UnicodeDecodeError:
        print(f"{f}: binary files differ"); sys.exit()
    for i in range(max(len(la), len(lb))):
        x = la[i] if i < len(la) else "<end>"; y = lb[i] if i < len(lb) else "<end>"
        if x != y:
            print(f"{f}: line {i + 1}: {x[:150]!r} vs {y[:150]!r}"); sys.exit()
PY
}

same=0
differs=0
: >"$outdir/results.txt"
for c in "${cases[@]}"; do
    name=${c%%|*}
    args=${c#*|}
    [[ "$name" =~ ${ONLY:-.} ]] || continue
    run_case before "$before_bin" "$name" "$args"
    run_case after "$after_bin" "$name" "$args"
    for side in before after; do
        python3 "$outdir/normalise.py" "$outdir/$side/out/$name" "$outdir/norm/$side/$name" "$outdir/$side"
    done
    if diff -r -q "$outdir/norm/before/$name" "$outdir/norm/after/$name" >/dev/null; then
        line="same     $name (exit $(cat "$outdir/before/out/$name/exit"))"
        same=$((same + 1))
    else
        files=$(diff -r -q "$outdir/norm/before/$name" "$outdir/norm/after/$name" |
            sed -E "s#^Files $outdir/norm/before/$name/([^ ]*) and .*#\\1#; s#^Only in $outdir/norm/(before|after)/$name/?([^:]*): (.*)#only \\1: \\3#" |
            tr '\n' ' ')
        line="differs  $name [${files% }]: $(first_difference "$outdir/norm/before/$name" "$outdir/norm/after/$name")"
        if [[ -n "${varies[$name]:-}" ]]; then
            line="$line (varies between two runs of one binary: ${varies[$name]})"
        fi
        differs=$((differs + 1))
    fi
    echo "$line" | tee -a "$outdir/results.txt"
done
echo "total: $((same + differs)) cases, $same same, $differs differ" | tee -a "$outdir/results.txt"
[[ $differs -eq 0 ]]
