#!/bin/bash
# Threads on a busy machine (docs/performance.md, "Threads"): idle and beside one busy
# process, in interleaved rounds, medians.
# 1. `sluice bench` on the 20k dam break, 1 and 2 threads, with the program's wait policy
#    and with libgomp's default spin (GOMP_SPINCOUNT=300000): us per particle-step.
# 2. `sluice simulate` of its first 0.5 s with the thread governor (no --threads) and with
#    --threads 1 and 2: wall seconds.
#   scripts/thread_load.sh [ROUNDS=5] [STEPS=150] [SLUICE=build/sluice]
set -euo pipefail
rounds=${1:-5}; steps=${2:-150}; exe=${3:-build/sluice}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"; kill $busy 2>/dev/null || true' EXIT
busy=
one() {  # one(load, label, threads, env...)
  local load=$1 label=$2 t=$3; shift 3
  local v
  v=$(env "$@" timeout 300 "$exe" bench scenes/dam_break.json --steps "$steps" --repeat 1 --threads "$t" \
      --csv "$tmp/b.csv" 2>/dev/null | awk '$1 == "dam_break" {print $9}')
  echo "$load,$label,$t,${v:-nan}" >> "$tmp/all.csv"
}
run() {  # run(load, label, flags...): wall seconds of simulate
  local load=$1 label=$2; shift 2
  local s e
  rm -rf "$tmp/run"
  s=$(date +%s.%N)
  env -u OMP_NUM_THREADS "$exe" simulate scenes/dam_break.json -o "$tmp/run" --duration 0.5 -q "$@" >/dev/null 2>&1 || true
  e=$(date +%s.%N)
  echo "$load,simulate $label,-,$(echo "$e - $s" | bc)" >> "$tmp/all.csv"
}
for r in $(seq "$rounds"); do
  for load in idle loaded; do
    if [ "$load" = loaded ]; then sh -c 'while :; do :; done' & busy=$!; fi
    one "$load" program 1 X=1
    one "$load" program 2 X=1
    one "$load" spin300k 2 GOMP_SPINCOUNT=300000
    run "$load" governor
    run "$load" threads_1 --threads 1
    run "$load" threads_2 --threads 2
    if [ "$load" = loaded ]; then kill "$busy"; wait "$busy" 2>/dev/null || true; busy=; fi
  done
done
echo "load,run,threads,median (us per particle-step; simulate: wall s),runs"
cut -d, -f1-3 "$tmp/all.csv" | sort -u | while IFS=, read -r load label t; do
  vals=$(awk -F, -v k="$load,$label,$t" '$1 "," $2 "," $3 == k {print $4}' "$tmp/all.csv" | sort -g)
  m=$(echo "$vals" | wc -l)
  echo "$load,$label,$t,$(echo "$vals" | sed -n "$(( (m + 1) / 2 ))p"),$m"
done
