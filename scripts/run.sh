#!/usr/bin/env bash
# scripts/run.sh - build gapbeam (release profile) and run one deck, then plot its results.
#
# Usage:
#   scripts/run.sh [DECK] [OVERRIDE ...]
#   scripts/run.sh inputs/moon_shaw_10p5hz.nml "&forcing frequency_hz=10.2 /"
#   scripts/run.sh "&forcing frequency_hz=10.2 /"      (default deck, with an override)
#
# DECK defaults to inputs/moon_shaw_10p5hz.nml if that exists, else inputs/moon_shaw_modes.nml.
# Each OVERRIDE is a namelist fragment, passed to the program verbatim after the deck (an argument
# starting with '&' in first place is taken as an override of the default deck).
# The program runs in the repository root, so a deck's relative output prefix (results/...) lands in
# the repository's results/ (created if missing) wherever run.sh is called from; a relative DECK is
# taken from the caller's directory and handed on relative to the root (or absolute if outside it).
#
# Steps: source scripts/setup.sh (installs what is missing); `fpm build --profile release`, quiet on
# success (the build log is shown only when the build fails); run the built `gapbeam` executable
# directly; read the program's `analysis: <word>` and `output: <prefix>` lines and, if
# scripts/plot.sh exists and is executable, call `scripts/plot.sh <analysis> <prefix>`.
# OMP_NUM_THREADS is left alone if set (default: the number of available cores);
# OPENBLAS_NUM_THREADS=1 (OpenMP parallelism is across sweep cases, not inside BLAS).
# Exit status: the program's; or 1 when the build fails; or plot.sh's when that fails. After
# status 5 (a sweep with failed points, all files written) the plots are made as after 0.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
caller_dir=${PWD}
cd "${root}"

if [[ ${1:-} == -h || ${1:-} == --help ]]; then
   sed -n '2,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' scripts/run.sh
   exit 0
fi

# shellcheck source=setup.sh
source "${root}/scripts/setup.sh"

# The deck: first argument unless it is an override (or absent).
if [[ $# -gt 0 && ${1:0:1} != '&' ]]; then
   deck=$1
   shift
   if [[ ${deck} != /* && ${caller_dir} != "${root}" ]]; then
      deck=$(realpath -m -s --relative-base="${root}" -- "${caller_dir}/${deck}")
   fi
elif [[ -f inputs/moon_shaw_10p5hz.nml ]]; then
   deck=inputs/moon_shaw_10p5hz.nml
else
   deck=inputs/moon_shaw_modes.nml
fi

export OPENBLAS_NUM_THREADS=1
if [[ -z ${OMP_NUM_THREADS+set} ]]; then
   OMP_NUM_THREADS=$(nproc 2>/dev/null || echo 1)
   export OMP_NUM_THREADS
fi

# Build, quietly.
build_log=$(mktemp "${TMPDIR:-/tmp}/gapbeam-build-release-XXXXXX")
printf '%s\n' "run: fpm build --profile release (in ${root})" >"${build_log}"
if ! fpm build --profile release >>"${build_log}" 2>&1; then
   cat "${build_log}" >&2
   printf 'run: error: the release build failed (log %s)\n' "${build_log}" >&2
   exit 1
fi

# The executable's path: fpm prints it with `--runner echo`; build progress lines and
# "Project is up to date" are not paths of executable files, so they are skipped.
exe=""
while IFS= read -r line; do
   [[ ${line} == /* ]] || line=${root}/${line}
   if [[ -f ${line} && -x ${line} ]]; then exe=${line}; fi
done < <(fpm run --profile release --runner echo gapbeam 2>>"${build_log}")
if [[ -z ${exe} ]]; then
   cat "${build_log}" >&2
   printf 'run: error: cannot find the gapbeam executable (fpm run --runner echo; log %s)\n' \
      "${build_log}" >&2
   exit 1
fi
rm -f "${build_log}"

mkdir -p results

# Run: stdout goes to the terminal and to a file that is scanned for the analysis and output lines.
stdout_copy=$(mktemp "${TMPDIR:-/tmp}/gapbeam-run-XXXXXX")
trap 'rm -f "${stdout_copy}"' EXIT
status=0
# Unbuffered, so that progress lines show as they come although stdout is a pipe.
GFORTRAN_UNBUFFERED_PRECONNECTED=y "${exe}" "${deck}" "$@" | tee "${stdout_copy}" || status=$?
# status 5: a sweep whose files are all written but some of whose points failed: plotted (the
# charts mark the failed points), then that status is returned
run_status=${status}
if [[ ${status} -ne 0 && ${status} -ne 5 ]]; then
   printf 'run: gapbeam exited with status %d\n' "${status}" >&2
   exit "${status}"
fi

# The last `analysis:` and `output:` lines (leading blanks and trailing blanks ignored).
analysis=$(sed -n 's/^[[:space:]]*analysis:[[:space:]]*//p' "${stdout_copy}" | tail -n 1 \
   | sed 's/[[:space:]]*$//')
prefix=$(sed -n 's/^[[:space:]]*output:[[:space:]]*//p' "${stdout_copy}" | tail -n 1 \
   | sed 's/[[:space:]]*$//')

plot=${root}/scripts/plot.sh
if [[ -f ${plot} && -x ${plot} ]]; then
   if [[ -z ${analysis} || -z ${prefix} ]]; then
      printf "run: warning: no 'analysis:' or 'output:' line in the program's output; not plotting\n" >&2
      exit 0
   fi
   status=0
   "${plot}" "${analysis}" "${prefix}" || status=$?
   if [[ ${status} -ne 0 ]]; then
      printf 'run: error: scripts/plot.sh %s %s failed with status %d (results are in %s.h5)\n' \
         "${analysis}" "${prefix}" "${status}" "${prefix}" >&2
      exit "${status}"
   fi
fi
if [[ ${run_status} -eq 5 ]]; then
   printf 'run: gapbeam exited with status 5: some sweep points failed (listed above, marked in the files)\n' >&2
fi
exit "${run_status}"
