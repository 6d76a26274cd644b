#!/usr/bin/env bash
# scripts/bench_tubes.sh - full against reduced tube models: speed and accuracy side by side.
#
# Usage:
#   scripts/bench_tubes.sh [--parts deck,periodic,map]      (from anywhere)
#
# Builds the release profile (quietly), finds the gapbeam_bench_tubes example and gapbeam, and
# runs scripts/bench_tubes.py: on inputs/tube_multispan.nml the full model and the default
# (reduced, &reduction kind = 'auto') run side by side at the deck's tolerance, the full model's
# own spread between tolerances, reduced models at several cut-offs and tolerances, where the
# steps go; the same tube in a periodic regime (the truncation error of the basis alone); the
# tube map inputs/tube_map.nml full and reduced (CPU and contact classes of its 45 points).
# Writes bench_results/tubes_reduction.txt (tables), .dat (one line per run) and .png (the chart,
# scripts/tubes_reduction.gp: work-rate error against CPU per simulated second).
#
# Runs are cached in bench_results/tubes_reduction.cache/ (keyed by the deck, the variant and the
# executables): a second call re-runs only what changed. BENCH_TUBES_FRESH=1 runs everything
# again; BENCH_TUBES_TRANSIENT / BENCH_TUBES_RECORD set the deck case's periods (30 / 40, the
# deck's own). BENCH_LOCK=FILE runs every case under `flock FILE` (nothing else shares the CPU
# while it runs). BENCH_TUBES_MAP='&sweep n_frequency = 5, n_y = 3 /' (any namelist fragment)
# runs a subset of the map's points; BENCH_TUBES_CASES='periodic deck' draws the periodic
# panel of the chart too (default 'deck'). BENCH_TUBES_QUICK=1 runs the deck part's side-by-side
# set only (full, default, rk45 and exponential at 1e-4, the full model at 1e-6 as the reference,
# the exponential integrator at 1e-3, 1e-5 and 1e-6, the full model under it at 1e-4);
# BENCH_TUBES_PERIODIC_QUICK=1 the periodic part's short set (the full and default models at
# 1e-4, the exponential integrator on the 'auto' basis at 1e-3 .. 1e-6 and on the full model at
# 1e-4, against the full model at 1e-6). The whole benchmark costs about an hour of CPU (the full model at tolerance
# 1e-6 on 70 periods alone takes about 6 minutes); every run is serial.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "${root}"

if [[ ${1:-} == -h || ${1:-} == --help ]]; then
   sed -n '2,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' scripts/bench_tubes.sh
   exit 0
fi

# shellcheck source=setup.sh
source "${root}/scripts/setup.sh"
export OPENBLAS_NUM_THREADS=1

build_log=$(mktemp "${TMPDIR:-/tmp}/gapbeam-build-release-XXXXXX")
lock=()
[[ -n ${BENCH_LOCK:-} ]] && lock=(flock "${BENCH_LOCK}")
if ! "${lock[@]}" fpm build --profile release >>"${build_log}" 2>&1; then
   cat "${build_log}" >&2
   printf 'bench_tubes: error: the release build failed (log %s)\n' "${build_log}" >&2
   exit 1
fi
find_exe() {
   local found="" line
   while IFS= read -r line; do
      [[ ${line} == /* ]] || line=${root}/${line}
      if [[ -f ${line} && -x ${line} ]]; then found=${line}; fi
   done < <(fpm run --profile release "$@" --runner echo 2>>"${build_log}")
   printf '%s' "${found}"
}
bench=$(find_exe --example gapbeam_bench_tubes)
gapbeam=$(find_exe gapbeam)
if [[ -z ${bench} || -z ${gapbeam} ]]; then
   cat "${build_log}" >&2
   printf 'bench_tubes: error: cannot find gapbeam_bench_tubes or gapbeam (log %s)\n' \
      "${build_log}" >&2
   exit 1
fi
rm -f "${build_log}"
# copies: a rebuild while the benchmark runs must not change the executables under it
mkdir -p bench_results/tubes_reduction.cache
cp "${bench}" bench_results/tubes_reduction.cache/gapbeam_bench_tubes
cp "${gapbeam}" bench_results/tubes_reduction.cache/gapbeam
python3 scripts/bench_tubes.py bench_results/tubes_reduction.cache/gapbeam_bench_tubes \
   bench_results/tubes_reduction.cache/gapbeam --out bench_results/tubes_reduction "$@"
gnuplot -e "datafile='bench_results/tubes_reduction.dat'; outfile='bench_results/tubes_reduction.png'; cases='${BENCH_TUBES_CASES:-deck}'" \
   scripts/tubes_reduction.gp
printf 'bench_tubes: bench_results/tubes_reduction.txt, .dat, .png\n'
