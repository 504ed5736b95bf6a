#!/bin/bash
# Threads on a busy machine (issue "Speed", part 4): the 20k dam break on 1 and 2 threads,
# idle and beside one busy process, with the program's wait policy and with libgomp's
# default spin (GOMP_SPINCOUNT=300000), interleaved rounds, medians of us/particle-step.
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
for r in $(seq "$rounds"); do
  for load in idle loaded; do
    if [ "$load" = loaded ]; then sh -c 'while :; do :; done' & busy=$!; fi
    one "$load" program 1 X=1
    one "$load" program 2 X=1
    one "$load" spin300k 2 GOMP_SPINCOUNT=300000
    if [ "$load" = loaded ]; then kill "$busy"; wait "$busy" 2>/dev/null || true; busy=; fi
  done
done
echo "load,policy,threads,median_us_per_particle_step,runs"
cut -d, -f1-3 "$tmp/all.csv" | sort -u | while IFS=, read -r load label t; do
  vals=$(awk -F, -v k="$load,$label,$t" '$1 "," $2 "," $3 == k {print $4}' "$tmp/all.csv" | sort -g)
  m=$(echo "$vals" | wc -l)
  echo "$load,$label,$t,$(echo "$vals" | sed -n "$(( (m + 1) / 2 ))p"),$m"
done
