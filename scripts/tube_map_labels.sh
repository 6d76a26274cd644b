#!/usr/bin/env bash
# scripts/tube_map_labels.sh - the tube map of inputs/tube_map.nml labelled with Lyapunov
# exponents (ring supports, friction; docs/tubes.md, "The work-rate map"), its cost against the
# unlabelled map, and the check of the labels of one integrator against another's on one row:
#   row:     the 0.2 mm row (9 frequencies) labelled under METHOD and under the deck's default
#            method (Newmark): labels and exponents side by side (difference / combined sigma);
#   map:     the whole 45-point map labelled and unlabelled under METHOD, one after the other:
#            label counts, CPU of each and their ratio; the chaos map chart;
#   persist: every chaotic point of the labelled map run again as a transient job with
#            PERSIST_PERIODS transient periods (default 300, 20 x the map's 15) and the same
#            exponent settings: a point no longer chaotic there is a chaotic transient.
# The exponent settings are those of bench_results/tube_map_labels.txt:
# lyapunov_periods = 50, lyapunov_max_periods = 200. The period tolerance is set to 1e-2, the
# automatic one of the map's tolerance 1e-3 under Newmark (10 x the tolerance), so that every
# method labels against the same one (the automatic period tolerance of the embedded methods,
# rk45 and exponential, is 10 x rk_rtol, 1e-5 here, though their steps run under the map's
# tolerance).
#
# Usage:
#   scripts/tube_map_labels.sh [OUTDIR] [PARTS]     (default results/tube_map_labels, 'row map persist')
#   METHOD=exponential (default) | rk45 | newmark;  GAPBEAM=/path/to/gapbeam;
#   LOCK=LOCKFILE (each run holds this lock file when given); OMP_NUM_THREADS (default 2).
# Prints the summary (also OUTDIR/summary.txt). Cost (release, 2 threads, exponential): the
# row about 6.5 CPU minutes (5.6 of them the Newmark row), the map 4, persistence 3.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "${root}"
out=${1:-results/tube_map_labels}
parts=${2:-row map persist}
method=${METHOD:-exponential}
persist_periods=${PERSIST_PERIODS:-300}
export OPENBLAS_NUM_THREADS=1
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-2}
if [[ -n ${GAPBEAM:-} ]]; then
   exe=${GAPBEAM}
else
   fpm build --profile release >/dev/null
   exe=$(fpm run gapbeam --profile release --runner echo 2>/dev/null | tail -n 1)
   [[ ${exe} == /* ]] || exe=${root}/${exe}
fi
locked() {
   if [[ -n ${LOCK:-} ]]; then flock "${LOCK}" "$@"; else "$@"; fi
}
deck=inputs/tube_map.nml
lyap="&diagnostics lyapunov_periods = 50, lyapunov_max_periods = 200, period_tolerance = 1e-2 /"
solver="&solver method = '${method}' /"
row="&sweep n_y = 1, y_start = 0.2e-3, y_end = 0.2e-3 /"
py="python3 ${root}/scripts/tube_map_labels.py"
mkdir -p "${out}"
summary=${out}/summary.txt
{
   echo "tube_map_labels: $(date -u +%Y-%m-%dT%H:%MZ), commit $(git rev-parse --short HEAD)" \
        "$(git diff --quiet && echo clean || echo modified), method ${method}," \
        "${OMP_NUM_THREADS} thread(s), $(nproc --all) cores"
   echo "executable: ${exe}"
} >"${summary}"

if [[ " ${parts} " == *" row "* ]]; then
   locked "${exe}" "${deck}" "&job output = '${out}/row_${method}' /" "${solver}" "${row}" \
      "${lyap}" >"${out}/row_${method}.log" 2>&1
   locked "${exe}" "${deck}" "&job output = '${out}/row_newmark' /" "${row}" "${lyap}" \
      >"${out}/row_newmark.log" 2>&1
   {
      echo
      echo "== row 0.2 mm: ${method} | newmark (label, lambda +- sigma [1/s])"
      ${py} compare "${out}/row_${method}.h5" "${out}/row_newmark.h5"
   } >>"${summary}"
fi

if [[ " ${parts} " == *" map "* ]]; then
   locked "${exe}" "${deck}" "&job output = '${out}/map_labelled' /" "${solver}" "${lyap}" \
      >"${out}/map_labelled.log" 2>&1
   locked "${exe}" "${deck}" "&job output = '${out}/map_unlabelled' /" "${solver}" \
      "&diagnostics period_tolerance = 1e-2 /" >"${out}/map_unlabelled.log" 2>&1
   scripts/plot.sh sweep "${out}/map_labelled" >/dev/null 2>&1 || true
   {
      echo
      echo "== the whole map under ${method}: labelled, unlabelled"
      ${py} counts "${out}/map_labelled.h5" "${out}/map_unlabelled.h5"
      echo "per point (labelled):"
      ${py} points "${out}/map_labelled.h5"
   } >>"${summary}"
fi

if [[ " ${parts} " == *" persist "* ]]; then
   echo >>"${summary}"
   echo "== persistence: the chaotic points after ${persist_periods} transient periods" \
      >>"${summary}"
   # one transient run per chaotic point, single-threaded, OMP_NUM_THREADS of them at a time
   persist_one() {
      OMP_NUM_THREADS=1 "${exe}" "${deck}" \
         "&job analysis = 'transient', output = '${out}/persist_${1}Hz_${2}m' /" \
         "&forcing frequency_hz = ${1} /" "&stops gap = ${2}, ${2} /" \
         "&solver method = '${method}', transient_periods = ${persist_periods} /" \
         "&diagnostics lyapunov_periods = 50, lyapunov_max_periods = 200, period_tolerance = 1e-2, transient_max_periods = $((persist_periods + 100)) /" \
         >"${out}/persist_${1}Hz_${2}m.log" 2>&1
   }
   export -f persist_one
   export exe deck out method persist_periods
   ${py} chaotic "${out}/map_labelled.h5" >"${out}/chaotic_points.txt"
   locked xargs -P "${OMP_NUM_THREADS}" -L 1 bash -c 'persist_one "$0" "$1"' \
      <"${out}/chaotic_points.txt"
   while read -r f gap; do
      ${py} persist "${out}/persist_${f}Hz_${gap}m.h5" >>"${summary}"
   done <"${out}/chaotic_points.txt"
fi
cat "${summary}"
