#!/usr/bin/env bash
# scripts/bench.sh - build gapbeam (release profile) and run the speed benchmark gapbeam_bench.
#
# Usage:
#   scripts/bench.sh            (from anywhere)
#
# Steps: source scripts/setup.sh (installs what is missing); `fpm build --profile release`, quiet
# on success (the build log is shown only when the build fails); find the built `gapbeam_bench`
# example (`fpm run --profile release --example --runner echo gapbeam_bench`: it is an fpm
# example, so that `fpm run -- DECK` and `fpm install` concern gapbeam alone); run it from the
# repository root and copy its output (the table) to bench_results/bench.txt (git-ignored).
#
# The benchmark (bench/gapbeam_bench.f90) times run_transient on inputs/moon_shaw_10p5hz.nml,
# 300 + 1000 periods: fixed T/256 condensed without and with event location, fixed T/256 fixed
# point, half-step control with the deck's defaults and with the paper's fixed point, and a
# hand-written ceiling loop doing the arithmetic of the fixed-step condensed case; best of 3 runs
# each. Progress lines go to stderr, the table to stdout and the file.
# Then the model-size ladder (scripts/model_size_ladder.py): the same case at 4, 15, 30, 60, 120,
# 240 and 480 elements, 5 forcing periods from rest, with the exact integrator (the default for
# this piecewise-linear stop) and Newmark under error control at tolerance 1e-4 (the default for a
# Hertz stop): steps per period, CPU per simulated second, set-up CPU and the output error against
# the exact run, to bench_results/model_size_ladder.txt (.dat for plotting).
# BENCH_LADDER=0 skips the ladder; BENCH_ELEMENTS="4 15 30" sets its element counts.
# OPENBLAS_NUM_THREADS=1 and OMP_NUM_THREADS=1: the benchmark is serial (no BLAS in the step loop).
# Exit status: the benchmark's (1 when the ceiling loop does not reproduce the fixed-step run or a
# run fails); or 1 when the build fails.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "${root}"

if [[ ${1:-} == -h || ${1:-} == --help ]]; then
   sed -n '2,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' scripts/bench.sh
   exit 0
fi

# shellcheck source=setup.sh
source "${root}/scripts/setup.sh"

export OPENBLAS_NUM_THREADS=1
export OMP_NUM_THREADS=1

# Build, quietly.
build_log=$(mktemp "${TMPDIR:-/tmp}/gapbeam-build-release-XXXXXX")
printf '%s\n' "bench: fpm build --profile release (in ${root})" >"${build_log}"
if ! fpm build --profile release >>"${build_log}" 2>&1; then
   cat "${build_log}" >&2
   printf 'bench: error: the release build failed (log %s)\n' "${build_log}" >&2
   exit 1
fi

# The executable's path: fpm prints it with `--runner echo`; lines that are not paths of
# executable files (build progress, "Project is up to date") are skipped.
exe=""
while IFS= read -r line; do
   [[ ${line} == /* ]] || line=${root}/${line}
   if [[ -f ${line} && -x ${line} ]]; then exe=${line}; fi
done < <(fpm run --profile release --example --runner echo gapbeam_bench 2>>"${build_log}")
if [[ -z ${exe} ]]; then
   cat "${build_log}" >&2
   printf 'bench: error: cannot find the gapbeam_bench example (fpm run --example --runner echo; log %s)\n' \
      "${build_log}" >&2
   exit 1
fi
rm -f "${build_log}"

mkdir -p bench_results
GFORTRAN_UNBUFFERED_PRECONNECTED=y "${exe}" | tee bench_results/bench.txt

if [[ ${BENCH_LADDER:-1} != 0 ]]; then
   if ! python3 -c 'import numpy, h5py' >/dev/null 2>&1; then
      python3 -m pip install -q numpy h5py >&2
   fi
   gapbeam_exe=""
   while IFS= read -r line; do
      [[ ${line} == /* ]] || line=${root}/${line}
      if [[ -f ${line} && -x ${line} ]]; then gapbeam_exe=${line}; fi
   done < <(fpm run --profile release --runner echo gapbeam 2>/dev/null)
   # shellcheck disable=SC2086
   python3 scripts/model_size_ladder.py "${gapbeam_exe}" --elements ${BENCH_ELEMENTS:-4 15 30 60 120 240 480} \
      --out bench_results/model_size_ladder
fi
