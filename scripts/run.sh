#!/usr/bin/env bash
# scripts/run.sh - build gapbeam (release profile), run the main job or one deck, plot the results.
#
# Usage:
#   scripts/run.sh [--format png|pdf|svg]                 the main job (below)
#   scripts/run.sh [--format png|pdf|svg] DECK [OVERRIDE ...]   one deck
#   scripts/run.sh inputs/moon_shaw_10p5hz.nml "&forcing frequency_hz=10.2 /"
#   scripts/run.sh "&forcing frequency_hz=10.2 /"   (inputs/moon_shaw_10p5hz.nml with an override)
#
# The main job (no DECK): what gapbeam is for, in about a minute on 2 cores. Into results/main/:
#   line_4mm_up, line_4mm_down   inputs/sweep_line_4mm.nml over 8.4-11.0 Hz in 261 steps of
#                                0.01 Hz at 4.0 mm p-p, swept up and down (continuation): the
#                                bifurcation diagram with its period-doubling cascade and chaotic
#                                bands, and the hysteresis between the two directions
#   paper_10p5hz, paper_10p2hz, paper_9p8hz   the paper's three 4-element cases
#                                (inputs/moon_shaw_*.nml: lumped mass, translational masses
#                                only), the 9.8 Hz one with its state history (&output
#                                state_history: results/main/paper_9p8hz.xdmf for ParaView,
#                                paper_9p8hz.animation.gif)
#   paper_*_half_element, line_4mm_up_half_element   the three cases and the up sweep again
#                                with the former mass rule (the rotary inertia of the rigid half
#                                element, b = 6.6477523e-3 m): the sensitivity that
#                                docs/paper_regimes.md found
# then scripts/main_summary.py (the paper's claims, inputs/paper_claims.txt, against the labels in
# the result files: summary.txt, printed) and the summary figure results/main/summary.png
# (scripts/summary.gp), beside every run's own figures (scripts/plot.sh). The up and down sweeps run side
# by side (one thread each), the six cases after the down sweep, the second up sweep after the
# first; the first up sweep shows its progress.
# The last line says how long the job took.
#
# One DECK: each OVERRIDE is a namelist fragment passed to the program verbatim after the deck (an
# argument starting with '&' in first place is taken as an override of
# inputs/moon_shaw_10p5hz.nml). The program runs in the repository root, so a deck's relative
# output prefix (results/...) lands in the repository's results/ (created if missing) wherever
# run.sh is called from; a relative DECK is taken from the caller's directory. The program's
# `analysis:` and `output:` lines say what scripts/plot.sh should draw.
#
# --format: the figures as png (default), pdf or svg (scripts/plot.sh --format).
# Steps: source scripts/setup.sh (installs what is missing); `fpm build --profile release`, quiet on
# success (the build log is shown only when the build fails); GAPBEAM_GIT_COMMIT is exported from
# `git describe --always --dirty` (the result files record it). OMP_NUM_THREADS is left alone if
# set (default: the number of available cores); OPENBLAS_NUM_THREADS=1.
# Exit status: the program's; 1 when the build, a run of the main job or a figure fails. After
# status 5 (a sweep with failed points, all files written) the plots are made as after 0.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
caller_dir=${PWD}
cd "${root}"

if [[ ${1:-} == -h || ${1:-} == --help ]]; then
   sed -n '2,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' scripts/run.sh
   exit 0
fi
fmt=png
if [[ ${1:-} == --format ]]; then
   fmt=${2:-}
   shift 2 || true
elif [[ ${1:-} == --format=* ]]; then
   fmt=${1#--format=}
   shift
fi
case ${fmt} in
   png | pdf | svg) ;;
   *)
      printf "run: error: --format '%s': expected png, pdf or svg\n" "${fmt}" >&2
      exit 2
      ;;
esac

# shellcheck source=setup.sh
source "${root}/scripts/setup.sh"

main_job=0
if [[ $# -gt 0 && ${1:0:1} != '&' ]]; then
   deck=$1
   shift
   if [[ ${deck} != /* && ${caller_dir} != "${root}" ]]; then
      deck=$(realpath -m -s --relative-base="${root}" -- "${caller_dir}/${deck}")
   fi
elif [[ $# -gt 0 ]]; then
   deck=inputs/moon_shaw_10p5hz.nml
else
   main_job=1
fi

export OPENBLAS_NUM_THREADS=1
if [[ -z ${OMP_NUM_THREADS+set} ]]; then
   OMP_NUM_THREADS=$(nproc 2>/dev/null || echo 1)
   export OMP_NUM_THREADS
fi
GAPBEAM_GIT_COMMIT=$(git -C "${root}" describe --always --dirty 2>/dev/null || echo unknown)
export GAPBEAM_GIT_COMMIT

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
plot=${root}/scripts/plot.sh

if [[ ${main_job} -eq 1 ]]; then
   out=results/main
   mkdir -p "${out}"
   SECONDS=0
   line="&sweep frequency_start_hz = 8.4, frequency_end_hz = 11.0, n_frequency = 261, checkpoint = .false. /"
   # the lumped mass's rotary inertia of the rigid half element, with the width that gives
   # f1 = 4.3 Hz with it (inputs/derive_width.nml): the sensitivity of docs/paper_regimes.md
   half_element="&beam rotary_inertia = 'half_element', width = 6.6477523e-3 /"
   printf 'main: the paper'"'"'s three cases and the 4.0 mm line, 8.4-11.0 Hz up and down (2 x 261 points), into %s/\n' "${out}"
   # the down sweep, then the three cases, in the background (logs in results/main/*.log)
   (
      set -e
      OMP_NUM_THREADS=1 "${exe}" inputs/sweep_line_4mm.nml "${line}" "&sweep direction = 'down' /" \
         "&job title = 'Reference beam, 4.0 mm p-p, 8.4-11.0 Hz, swept down', output = '${out}/line_4mm_down' /" \
         --quiet >"${out}/line_4mm_down.log" 2>&1
      for c in 10p5hz 10p2hz 9p8hz; do
         extra=()
         if [[ ${c} == 9p8hz ]]; then extra=("&output state_history = .true. /"); fi
         OMP_NUM_THREADS=1 "${exe}" "inputs/moon_shaw_${c}.nml" "${extra[@]}" \
            "&job output = '${out}/paper_${c}' /" --quiet >"${out}/paper_${c}.log" 2>&1
         # the same case with the former mass rule (rigid half element, its own width)
         OMP_NUM_THREADS=1 "${exe}" "inputs/moon_shaw_${c}.nml" "${half_element}" \
            "&job output = '${out}/paper_${c}_half_element' /" --quiet \
            >"${out}/paper_${c}_half_element.log" 2>&1
      done
   ) &
   background=$!
   status=0
   OMP_NUM_THREADS=1 GFORTRAN_UNBUFFERED_PRECONNECTED=y "${exe}" inputs/sweep_line_4mm.nml \
      "${line}" "&job title = 'Reference beam, 4.0 mm p-p, 8.4-11.0 Hz, swept up', output = '${out}/line_4mm_up' /" \
      >"${out}/line_4mm_up.log" || status=$?
   # the up sweep again with the former mass rule: the paper's "period four becomes chaotic"
   OMP_NUM_THREADS=1 "${exe}" inputs/sweep_line_4mm.nml "${line}" "${half_element}" \
      "&job title = 'Reference beam with the rigid half element rotary inertia, 4.0 mm p-p, 8.4-11.0 Hz, swept up', output = '${out}/line_4mm_up_half_element' /" \
      --quiet >"${out}/line_4mm_up_half_element.log" 2>&1 || status=$?
   wait "${background}" || status=$?
   if [[ ${status} -ne 0 ]]; then
      printf 'run: error: a run of the main job failed (status %d); its log in %s/*.log:\n' \
         "${status}" "${out}" >&2
      grep -h '^error:' "${out}"/*.log >&2 || true
      exit 1
   fi
   for f in "${out}"/*.log; do
      sed -n "s#^\(attractor\|labels\): #main: $(basename "${f}" .log): #p" "${f}"
   done
   PYTHONPATH="${root}/python${PYTHONPATH:+:${PYTHONPATH}}" PYTHONDONTWRITEBYTECODE=1 \
      python3 scripts/main_summary.py "${out}" || exit 1
   for p in line_4mm_up line_4mm_down line_4mm_up_half_element; do
      "${plot}" --format "${fmt}" sweep "${out}/${p}" || exit 1
   done
   for c in 10p5hz 10p2hz 9p8hz 10p5hz_half_element 10p2hz_half_element 9p8hz_half_element; do
      "${plot}" --format "${fmt}" transient "${out}/paper_${c}" || exit 1
   done
   part="${out}/summary.${fmt}.part"
   if gnuplot -e "dir='${out}'; format='${fmt}'; outfile='${part}'" scripts/summary.gp \
      && [[ -s ${part} ]]; then
      mv -f "${part}" "${out}/summary.${fmt}"
      printf 'plot: wrote %s\n' "${out}/summary.${fmt}"
   else
      rm -f "${part}"
      printf 'run: error: the summary figure failed (scripts/summary.gp)\n' >&2
      exit 1
   fi
   printf 'main: done in %d s (wall); open %s/summary.%s first; ParaView: %s/paper_9p8hz.xdmf\n' \
      "${SECONDS}" "${out}" "${fmt}" "${out}"
   exit 0
fi

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

if [[ -f ${plot} && -x ${plot} ]]; then
   if [[ -z ${analysis} || -z ${prefix} ]]; then
      printf "run: warning: no 'analysis:' or 'output:' line in the program's output; not plotting\n" >&2
      exit 0
   fi
   status=0
   "${plot}" --format "${fmt}" "${analysis}" "${prefix}" || status=$?
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
