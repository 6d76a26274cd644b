#!/usr/bin/env bash
# scripts/bench_wear.sh - wear-output error against CPU on the tube decks, per method.
#
# Usage:
#   scripts/bench_wear.sh [--methods "newmark rk45"] [--decks "DECK ..."]
#                         [--tolerances "1e-3 1e-4 1e-5 1e-6 1e-7"] [--reference newmark:1e-8]
#                         [--override "&solver record_periods = 20 /"] [--out PREFIX]
#
# Builds the release profile and runs scripts/bench_wear.py: every deck (default
# test/decks/tube_cantilever.nml, the rattling tube) with every method (any that takes ring
# supports; a method that refuses the deck is listed as refused) at every tolerance, serial,
# certification off; per support the relative error of the normal work rate, the friction work
# rate and the sliding distance against one converged run (--reference METHOD:TOLERANCE), and the
# record's CPU per simulated second (/run/cpu_seconds). Writes bench_results/wear_error.txt
# (tables, with error / tolerance), .dat (one line per run and support) and .png (the chart,
# scripts/bench_wear.gp: error against CPU per simulated second, one panel per output).
# BENCH_LOCK=FILE runs the build and every case under `flock FILE`. The default costs about two
# minutes of CPU (the reference alone about one).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "${root}"

if [[ ${1:-} == -h || ${1:-} == --help ]]; then
   sed -n '2,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' scripts/bench_wear.sh
   exit 0
fi

# shellcheck source=setup.sh
source "${root}/scripts/setup.sh"
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1

out=bench_results/wear_error
args=()
while [[ $# -gt 0 ]]; do
   case $1 in
      --out) out=$2; shift 2 ;;
      --methods | --decks | --tolerances | --reference | --override) args+=("$1" "$2"); shift 2 ;;
      *) printf 'bench_wear: error: unknown argument %s (see --help)\n' "$1" >&2; exit 2 ;;
   esac
done

build_log=$(mktemp "${TMPDIR:-/tmp}/gapbeam-build-release-XXXXXX")
lock=()
[[ -n ${BENCH_LOCK:-} ]] && lock=(flock "${BENCH_LOCK}")
if ! "${lock[@]}" fpm build --profile release >>"${build_log}" 2>&1; then
   cat "${build_log}" >&2
   printf 'bench_wear: error: the release build failed (log %s)\n' "${build_log}" >&2
   exit 1
fi
gapbeam=""
while IFS= read -r line; do
   [[ ${line} == /* ]] || line=${root}/${line}
   if [[ -f ${line} && -x ${line} ]]; then gapbeam=${line}; fi
done < <(fpm run --profile release gapbeam --runner echo 2>>"${build_log}")
if [[ -z ${gapbeam} ]]; then
   cat "${build_log}" >&2
   printf 'bench_wear: error: cannot find the release gapbeam (log %s)\n' "${build_log}" >&2
   exit 1
fi
rm -f "${build_log}"
# a copy: a rebuild while the benchmark runs must not change the executable under it
work=$(mktemp -d "${TMPDIR:-/tmp}/gapbeam-bench-wear-XXXXXX")
trap 'rm -rf "${work}"' EXIT
cp "${gapbeam}" "${work}/gapbeam"
mkdir -p "$(dirname "${out}")"
lock_arg=()
[[ -n ${BENCH_LOCK:-} ]] && lock_arg=(--lock "${BENCH_LOCK}")
python3 scripts/bench_wear.py "${work}/gapbeam" --out "${out}" "${lock_arg[@]}" "${args[@]}"
gnuplot -e "datafile='${out}.dat'; outfile='${out}.png'" scripts/bench_wear.gp
printf 'bench_wear: %s.txt, .dat, .png\n' "${out}"
