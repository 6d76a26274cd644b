#!/usr/bin/env bash
# scripts/scipy_reference.sh - time SciPy's solve_ivp (the general-purpose alternative) against
# gapbeam on the work-precision case: 10.5 Hz, 3.7 mm p-p, 10 forcing periods from rest, 4 and 15
# elements.
#
# Usage:
#   scripts/scipy_reference.sh [4|15 ...]        (from anywhere; default: 4 15)
#   GAPBEAM=/path/to/gapbeam scripts/scipy_reference.sh   use this binary (no build)
#   SCIPY_REF_ARGS='--repeats 10 --max-seconds 120' scripts/scipy_reference.sh
#                                                extra arguments for scripts/scipy_reference.py
#
# Steps: installs numpy, scipy and h5py with pip (quietly) when python3 cannot import them; finds
# gapbeam (GAPBEAM, else `fpm build --profile release` after sourcing scripts/setup.sh, as
# scripts/bench.sh does); then for each case, all output under bench_results/ (git-ignored):
#   1. the reference runs of inputs/moon_shaw_10p5hz.nml with
#      "&solver transient_periods = 0, record_periods = 10 /" (15 elements: also
#      "&beam n_elem = 15 /" "&stops node = 16 /", and "&diagnostics lyapunov_periods = 0 /"):
#      method 'exact' (bench_results/scipy_<n>el.exact.h5),
#      trapezoidal fixed T/65536 (.trapezoidal.h5), RK4 fixed T/16384 (.rk4.h5). The reference
#      is the exact run unless its final state differs from the trapezoidal one by more than 1e-6
#      (relative, energy norm); then it is the RK4 run (the choice is printed).
#   2. gapbeam's own work-precision study, inputs/work_precision_<n>el.nml, output prefix
#      bench_results/work_precision_<n>el (its .wp_<series>.dat and .work_precision.txt).
#   3. scripts/scipy_reference.py: the SciPy ladders (RK45, DOP853, Radau, LSODA; with event
#      location and plain; rtol 1e-2 .. 1e-12) written next to gapbeam's files as
#      bench_results/work_precision_<n>el.wp_scipy_<method>[_events].dat, and gapbeam's methods
#      (exact, rk45, rk4, newmark half-step and fixed) run as transient jobs and scored against the same
#      reference (.wp_gapbeam_<series>.dat); the summary table goes to stdout and to
#      bench_results/scipy_reference_<n>el.txt.
# OMP_NUM_THREADS=1 and OPENBLAS_NUM_THREADS=1 (single-core timings). The 15-element case takes
# of the order of 15 minutes (SciPy's explicit methods are stability-limited there, and Radau at
# tight tolerances is slow; a ladder stops after a run longer than --max-seconds, default 60).
# Exit status: non-zero when an install, the build or a run fails.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "${root}"

if [[ ${1:-} == -h || ${1:-} == --help ]]; then
   sed -n '2,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' scripts/scipy_reference.sh
   exit 0
fi

export OPENBLAS_NUM_THREADS=1
export OMP_NUM_THREADS=1

# Python packages, quietly.
if ! python3 -c 'import numpy, scipy, h5py' >/dev/null 2>&1; then
   printf '%s\n' 'scipy_reference: installing numpy scipy h5py (pip)' >&2
   pip_log=$(mktemp "${TMPDIR:-/tmp}/gapbeam-pip-XXXXXX")
   if ! python3 -m pip install -q numpy scipy h5py >"${pip_log}" 2>&1; then
      cat "${pip_log}" >&2
      printf 'scipy_reference: error: pip install failed (log %s)\n' "${pip_log}" >&2
      exit 1
   fi
   rm -f "${pip_log}"
fi

# The gapbeam binary.
exe=${GAPBEAM:-}
if [[ -z ${exe} ]]; then
   # shellcheck source=setup.sh
   source "${root}/scripts/setup.sh"
   build_log=$(mktemp "${TMPDIR:-/tmp}/gapbeam-build-release-XXXXXX")
   if ! fpm build --profile release >"${build_log}" 2>&1; then
      cat "${build_log}" >&2
      printf 'scipy_reference: error: the release build failed (log %s)\n' "${build_log}" >&2
      exit 1
   fi
   while IFS= read -r line; do
      [[ ${line} == /* ]] || line=${root}/${line}
      if [[ -f ${line} && -x ${line} ]]; then exe=${line}; fi
   done < <(fpm run --profile release --runner echo gapbeam 2>>"${build_log}")
   if [[ -z ${exe} ]]; then
      cat "${build_log}" >&2
      printf 'scipy_reference: error: cannot find the gapbeam executable (log %s)\n' \
         "${build_log}" >&2
      exit 1
   fi
   rm -f "${build_log}"
fi
if [[ ! -x ${exe} ]]; then
   printf 'scipy_reference: error: %s is not an executable\n' "${exe}" >&2
   exit 1
fi

mkdir -p bench_results
run_length="&solver transient_periods = 0, record_periods = 10 /"
no_lyapunov="&diagnostics lyapunov_periods = 0 /"   # /final is before them; saves time
deck=inputs/moon_shaw_10p5hz.nml

# Run gapbeam quietly; show its output when it fails.
gapbeam_run() {
   local log
   log=$(mktemp "${TMPDIR:-/tmp}/gapbeam-run-XXXXXX")
   if ! "${exe}" "$@" >"${log}" 2>&1 || grep -q '^error:' "${log}"; then
      cat "${log}" >&2
      printf 'scipy_reference: error: gapbeam %s failed\n' "$*" >&2
      rm -f "${log}"
      return 1
   fi
   rm -f "${log}"
}

cases=("$@")
if [[ ${#cases[@]} -eq 0 ]]; then cases=(4 15); fi

for ne in "${cases[@]}"; do
   case ${ne} in
      4) size=() ;;
      15) size=("&beam n_elem = 15 /" "&stops node = 16 /") ;;
      *)
         printf 'scipy_reference: error: unknown case %s (4 or 15)\n' "${ne}" >&2
         exit 1
         ;;
   esac
   base=bench_results/scipy_${ne}el
   printf 'scipy_reference: %s elements: reference runs\n' "${ne}" >&2
   gapbeam_run "${deck}" "${run_length}" "${size[@]}" "&solver method = 'exact' /" \
      "${no_lyapunov}" "&job output='${base}.exact' /"
   gapbeam_run "${deck}" "${run_length}" "${size[@]}" \
      "&solver step_control='fixed', steps_per_period=65536 /" \
      "${no_lyapunov}" "&job output='${base}.trapezoidal' /"
   gapbeam_run "${deck}" "${run_length}" "${size[@]}" \
      "&solver method='rk4', step_control='fixed', steps_per_period=16384 /" \
      "${no_lyapunov}" "&job output='${base}.rk4' /"
   d_trap=$(python3 scripts/scipy_reference.py "${base}.trapezoidal.h5" "${base}.exact.h5" --diff-only)
   d_rk4=$(python3 scripts/scipy_reference.py "${base}.rk4.h5" "${base}.exact.h5" --diff-only)
   if python3 -c "import sys; sys.exit(0 if float(sys.argv[1]) <= 1e-6 else 1)" "${d_trap}"; then
      reference=${base}.exact.h5
      why="exact (differs from trapezoidal T/65536 by ${d_trap}, from RK4 T/16384 by ${d_rk4})"
   else
      reference=${base}.rk4.h5
      why="RK4 T/16384: exact differs from trapezoidal T/65536 by ${d_trap} > 1e-6 (from RK4 by ${d_rk4})"
   fi
   printf 'scipy_reference: %s elements: reference %s\n' "${ne}" "${why}" >&2

   printf 'scipy_reference: %s elements: gapbeam work_precision study\n' "${ne}" >&2
   wp=bench_results/work_precision_${ne}el
   gapbeam_run "inputs/work_precision_${ne}el.nml" "&job output='${wp}' /"

   rk4_min=128
   if [[ ${ne} == 15 ]]; then rk4_min=8192; fi   # RK4 is unstable at T/4096 with 15 elements
   printf 'scipy_reference: %s elements: SciPy ladders\n' "${ne}" >&2
   # shellcheck disable=SC2086  # SCIPY_REF_ARGS is a list of words on purpose
   {
      printf 'reference: %s\n' "${why}"
      python3 scripts/scipy_reference.py "${base}.exact.h5" "${reference}" --out "${wp}" \
         --title "SciPy solve_ivp, 10.5 Hz, 3.7 mm p-p, ${ne} elements" \
         --gapbeam "${exe}" --deck "${deck}" --override "${run_length}" \
         ${size[@]+"${size[@]/#/--override=}"} --rk4-min-steps "${rk4_min}" ${SCIPY_REF_ARGS:-}
   } | tee "bench_results/scipy_reference_${ne}el.txt"
done
