#!/usr/bin/env bash
# A/B speed of this working tree's build against another commit, side by side: builds REV
# in a worktree (build-ab/), then runs both programs on the same cases in interleaved rounds
# (A B, then B A, ...), so that a machine that slows down over the run slows both alike.
# Prints each round's ratio and their median, with the iterations and the errors of each,
# and writes CSV. Speed figures go in docs as such ratios, never in timed tests.
#
#   scripts/bench-ab.sh REV [CASE...] [--rounds N] [--threads N] [--set KEY=VALUE]... [--set-a KEY=VALUE]...
#                       [--scenes-b this|rev] [-o DIR]
#
# Cases (default: dam20k dam130k column2m):
#   dam20k    simulate scenes/dam_break.json, first 0.3 s (20k particles)
#   dam130k   simulate scenes/dam_break_130k.json, first 0.5 s
#   dam130k5s simulate scenes/dam_break_130k.json, all 5 s (the end-to-end case's simulation;
#             about 15-20 minutes a run on 2 cores)
#   column2m  simulate a 2 m column at rest, h = 0.01, dt = 1 ms, 0.5 s (scenes/column.json)
#   smoke     simulate scenes/dam_break.json, first 0.02 s (a check of this script)
# --rounds N (default 3), --threads N (default: all cores, fixed for both programs),
# --set KEY=VALUE (repeatable): a scene override for both programs (an option both have, to
# time a change to it, e.g. solver.pressure_solver=multilevel against a commit that has it);
# --set-a KEY=VALUE (repeatable): a scene override for this tree's program only (an option
# that REV does not have, e.g. solver.pressure_solver=multilevel), named in the CSVs;
# --scenes-b this|rev (default this): the scene files B reads. Both programs read this tree's
# by default (a change to the code, on the same scenes); with rev, B reads REV's own (each
# commit's scenes as it ships them: a scene whose settings changed, or that REV cannot read).
# A case whose scene differs between the two trees is named on the output either way.
# -o DIR (default out/bench-ab/REV): runs.csv (one row per run) and ratios.csv (per case:
# the median ratio, its range, iterations, errors and mean neighbour-phase and pressure
# milliseconds per step of each). The ratio is REV's wall time per simulated second over
# this build's: above 1, this build is faster.
set -euo pipefail
cd "$(dirname "$0")/.."

rev="" rounds=3 threads=$(nproc) out="" cases=() a_sets=() both_sets=() scenes_b=this
while [ $# -gt 0 ]; do
  case "$1" in
    --rounds) rounds="${2:?--rounds needs a number}"; shift 2 ;;
    --threads) threads="${2:?--threads needs a number}"; shift 2 ;;
    -o) out="${2:?-o needs a directory}"; shift 2 ;;
    --scenes-b)
      case "${2:-}" in this|rev) scenes_b=$2 ;; *) echo "bench-ab: --scenes-b must be this or rev, got '${2:-}'" >&2; exit 2 ;; esac
      shift 2 ;;
    --set-a)
      case "${2:-}" in *=*) a_sets+=(--set "$2") ;; *) echo "bench-ab: --set-a needs KEY=VALUE, got '${2:-}'" >&2; exit 2 ;; esac
      shift 2 ;;
    --set)
      case "${2:-}" in *=*) both_sets+=(--set "$2") ;; *) echo "bench-ab: --set needs KEY=VALUE, got '${2:-}'" >&2; exit 2 ;; esac
      shift 2 ;;
    -h|--help) sed -n '2,30p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "bench-ab: unknown flag '$1' (see --help)" >&2; exit 2 ;;
    *) if [ -z "$rev" ]; then rev=$1; else cases+=("$1"); fi; shift ;;
  esac
done
[ -n "$rev" ] || { echo "bench-ab: usage: scripts/bench-ab.sh REV [CASE...] [--rounds N] [--threads N] [--set KEY=VALUE]... [--set-a KEY=VALUE]... [--scenes-b this|rev] [-o DIR]" >&2; exit 2; }
case "$rounds" in ''|*[!0-9]*|0) echo "bench-ab: --rounds '$rounds' must be a whole number >= 1" >&2; exit 2 ;; esac
case "$threads" in ''|*[!0-9]*|0) echo "bench-ab: --threads '$threads' must be a whole number >= 1" >&2; exit 2 ;; esac
[ ${#cases[@]} -gt 0 ] || cases=(dam20k dam130k column2m)

# case_args CASE: the simulate arguments of a case.
case_args() {
  case "$1" in
    dam20k) echo "scenes/dam_break.json --duration 0.3" ;;
    dam130k) echo "scenes/dam_break_130k.json --duration 0.5" ;;
    dam130k5s) echo "scenes/dam_break_130k.json --duration 5" ;;
    column2m) echo "scenes/column.json --set spacing=0.01 --set time.dt=1e-3 --set fluid.0.max=[0.5,2] --set boundaries.0.max=[0.5,5] --set time.duration=0.5" ;;
    smoke) echo "scenes/dam_break.json --duration 0.02" ;;
    *) return 1 ;;
  esac
}
for c in "${cases[@]}"; do
  case_args "$c" >/dev/null || { echo "bench-ab: unknown case '$c' (dam20k, dam130k, dam130k5s, column2m, smoke)" >&2; exit 2; }
done

sha=$(git rev-parse --verify --quiet "$rev^{commit}") || { echo "bench-ab: '$rev' is not a commit here" >&2; exit 2; }
short=${sha:0:7}
head=$(git rev-parse --short HEAD)$(git diff --quiet HEAD -- src CMakeLists.txt || echo "+changes")
# The overrides name A in the CSVs: "abc1234(key=value;key=value)".
if [ ${#a_sets[@]} -gt 0 ]; then
  label=""
  for ((k = 1; k < ${#a_sets[@]}; k += 2)); do label+="${label:+;}${a_sets[k]}"; done
  head="$head($label)"
fi
# Overrides of both name both: "abc1234[key=value]".
if [ ${#both_sets[@]} -gt 0 ]; then
  label=""
  for ((k = 1; k < ${#both_sets[@]}; k += 2)); do label+="${label:+;}${both_sets[k]}"; done
  head="$head[$label]"
  short_label="$short[$label]"
fi
out=${out:-out/bench-ab/$short}
mkdir -p "$out"

# A: this tree's program; B: REV's, built once in build-ab/ and kept for later runs.
./scripts/build.sh >/dev/null 2>&1 || { echo "bench-ab: scripts/build.sh failed" >&2; exit 1; }
a_bin=$PWD/build/sluice
src=build-ab/src-$short bld=build-ab/build-$short
if [ ! -x "$bld/sluice" ]; then
  echo "bench-ab: building $short in $bld"
  [ -d "$src" ] || git worktree add --detach "$src" "$sha" >/dev/null
  mkdir -p "$bld"
  { cmake -S "$src" -B "$bld" -DCMAKE_BUILD_TYPE=Release -DSLUICE_BUILD_TESTS=OFF &&
    cmake --build "$bld" -j"$(nproc)" --target sluice; } >"$bld.log" 2>&1 ||
    { tail -20 "$bld.log" >&2; echo "bench-ab: the build of $short failed ($bld.log)" >&2; exit 1; }
fi
b_bin=$PWD/$bld/sluice
# Each case's scene (the first word of its arguments): named when it differs between the trees.
for c in "${cases[@]}"; do
  scene=$(case_args "$c" | cut -d' ' -f1)
  git diff --quiet "$sha" -- "$scene" ||
    echo "bench-ab: $scene differs between this tree and $short; B reads $([ "$scenes_b" = rev ] && echo "$short's" || echo "this tree's") (--scenes-b)"
done

runs=$out/runs.csv
echo "round,case,build,commit,wall_s,simulated_s,wall_per_simulated_s,steps,iterations,avg_error_percent,max_error_percent,ms_neighbors,ms_pressure" >"$runs"
# run ROUND CASE A|B: one simulate, its totals appended to runs.csv.
run() {
  local bin=$a_bin commit=$head dir=$out/run_$3
  [ "$3" = B ] && bin=$b_bin commit=${short_label:-$short}
  local args
  read -ra args <<<"$(case_args "$2")"  # words, never globbed ([0.5,2])
  [ "$3" = B ] && [ "$scenes_b" = rev ] && args[0]=$src/${args[0]}
  args+=("${both_sets[@]}")
  [ "$3" = A ] && args+=("${a_sets[@]}")
  timeout 3600 "$bin" simulate "${args[@]}" --threads "$threads" -q -o "$dir" --overwrite >"$dir.log" 2>&1 ||
    { cat "$dir.log" >&2; echo "bench-ab: $3 ($commit) failed on $2 in round $1" >&2; exit 1; }
  python3 - "$dir/summary.json" "$1,$2,$3,$commit" "$dir/stats.csv" >>"$runs" <<'EOF'
import csv, json, sys
t = json.load(open(sys.argv[1]))["totals"]
wall, sim = t["wall_seconds"], t["simulated_time"]
steps = list(csv.DictReader(open(sys.argv[3])))  # the phases' mean milliseconds per step
ms = lambda k: sum(float(r[k]) for r in steps) / max(len(steps), 1)
print(f"{sys.argv[2]},{wall:.3f},{sim:.4f},{wall / sim:.3f},{t['steps']},{t['average_iterations']:.3f},"
      f"{t['average_error_percent']:.4f},{t['max_error_percent']:.4f},{ms('ms_neighbors'):.3f},{ms('ms_pressure'):.3f}")
EOF
}

echo "bench-ab: A = this tree ($head), B = $short; ${cases[*]}; $rounds rounds, $threads threads; B reads $scenes_b scenes"
for ((r = 1; r <= rounds; ++r)); do
  for c in "${cases[@]}"; do
    if ((r % 2)); then run "$r" "$c" A; run "$r" "$c" B; else run "$r" "$c" B; run "$r" "$c" A; fi
    tail -n 2 "$runs" | python3 -c "
import sys
rows = {l.split(',')[2]: l.strip().split(',') for l in sys.stdin}
a, b = rows['A'], rows['B']
print(f'  round {a[0]} {a[1]:9s} A {float(a[6]):8.2f} s/sim_s  B {float(b[6]):8.2f} s/sim_s  ratio B/A {float(b[6]) / float(a[6]):.3f}')"
  done
done

python3 - "$runs" "$out/ratios.csv" "$head" "$short" <<'EOF'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
head, short = sys.argv[3], sys.argv[4]
out = open(sys.argv[2], "w")
out.write("case,a,b,rounds,median_ratio,min_ratio,max_ratio,a_median_wall_per_sim_s,b_median_wall_per_sim_s,"
          "a_iterations,b_iterations,a_avg_error_percent,b_avg_error_percent,a_max_error_percent,b_max_error_percent,"
          "a_ms_neighbors,b_ms_neighbors,a_ms_pressure,b_ms_pressure\n")
print(f"\nratio = B's wall per simulated second / A's (above 1: A = {head} is faster than B = {short})")
print(f"{'case':9s} {'rounds':>6s} {'median':>7s} {'range':>13s} {'A s/sim_s':>10s} {'B s/sim_s':>10s} "
      f"{'A iters':>8s} {'B iters':>8s} {'A err %':>8s} {'B err %':>8s} {'A nbr ms':>8s} {'B nbr ms':>8s}")
for case in dict.fromkeys(r["case"] for r in rows):
    by = {(r["round"], r["build"]): r for r in rows if r["case"] == case}
    rounds = sorted({k[0] for k in by}, key=int)
    ratios = [float(by[(n, "B")]["wall_per_simulated_s"]) / float(by[(n, "A")]["wall_per_simulated_s"]) for n in rounds]
    med = lambda b, f: statistics.median(float(by[(n, b)][f]) for n in rounds)
    vals = [statistics.median(ratios), min(ratios), max(ratios), med("A", "wall_per_simulated_s"),
            med("B", "wall_per_simulated_s"), med("A", "iterations"), med("B", "iterations"),
            med("A", "avg_error_percent"), med("B", "avg_error_percent"), med("A", "max_error_percent"),
            med("B", "max_error_percent"), med("A", "ms_neighbors"), med("B", "ms_neighbors"), med("A", "ms_pressure"),
            med("B", "ms_pressure")]
    out.write(f"{case},{head},{short},{len(rounds)}," + ",".join(f"{v:.4g}" for v in vals) + "\n")
    print(f"{case:9s} {len(rounds):6d} {vals[0]:7.3f} {vals[1]:6.3f}-{vals[2]:<6.3f} {vals[3]:10.2f} {vals[4]:10.2f} "
          f"{vals[5]:8.2f} {vals[6]:8.2f} {vals[7]:8.4f} {vals[8]:8.4f} {vals[11]:8.2f} {vals[12]:8.2f}")
EOF
echo "bench-ab: wrote $runs and $out/ratios.csv"
