#!/usr/bin/env bash
# scripts/paper_regimes.sh - the paper-regime study (issue 11, item 6): the regime of the
# reference beam over 9-11.5 Hz against the model choices the paper leaves open, and where the
# paper's three cases (10.5 Hz / 3.7 mm, 10.2 and 9.8 Hz / 4.0 mm) fall.
#
# Usage:
#   scripts/paper_regimes.sh [OUTDIR]        (default results/paper_regimes)
#   GAPBEAM=/path/to/gapbeam scripts/paper_regimes.sh [OUTDIR]   (that executable, no build)
#
# Runs inputs/paper_regimes.nml (a sweep: x = frequency 9-11.5 Hz every 0.1 Hz, y = one model
# choice) with overrides, one sweep per row group:
#   k_theta_<mass>     y = &root k_theta (the root spring, hence f1), 8 values 0.055-0.15 N m/rad
#   rule_factor_<mass> y = &stops rule_factor (the stop stiffness: paper 2), 1-10
# for every mass model <mass>: lumped with rotary inertia 'half_element' (the reference), 'hrz'
# and 'none', and the consistent mass; and once
#   paper_integrator   the reference model with the paper's integrator (Newmark, half-step
#                      residual 1 % of the force terms, fixed-point stop force), y = k_theta
#                      0.0912 N m/rad (the labels are certified against the exact integrator)
# then prints the summary of scripts/paper_regimes.py (also written to OUTDIR/summary.md).
# Every point's label is certified (&diagnostics certify, the default). Cost: about 1500
# points, 8 CPU minutes on one core (release build); OMP_NUM_THREADS is used as given.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "${root}"
out=${1:-results/paper_regimes}
# shellcheck source=setup.sh
source "${root}/scripts/setup.sh"
export OPENBLAS_NUM_THREADS=1
if [[ -n ${GAPBEAM:-} ]]; then
   exe=${GAPBEAM}                  # a given executable (e.g. a copy, while the tree is edited)
else
   fpm build --profile release >/dev/null
   exe=$(fpm run gapbeam --profile release --runner echo 2>/dev/null | tail -n 1)
   [[ ${exe} == /* ]] || exe=${root}/${exe}
fi
mkdir -p "${out}"
deck=inputs/paper_regimes.nml

masses=(half_element hrz none consistent)
mass_override() {
   case $1 in
      consistent) printf "&beam mass_matrix = 'consistent' /" ;;
      *) printf "&beam mass_matrix = 'lumped', rotary_inertia = '%s' /" "$1" ;;
   esac
}

run() {   # run NAME OVERRIDE...
   local name=$1
   shift
   local t0=${SECONDS} status=0
   "${exe}" "${deck}" "&job output = '${out}/${name}', title = 'Paper regimes: ${name}' /" "$@" \
      >"${out}/${name}.log" 2>&1 || status=$?
   printf 'paper_regimes: %-28s exit %d, %4d s wall: %s\n' "${name}" "${status}" \
      "$((SECONDS - t0))" "$(grep -m1 '^labels:' "${out}/${name}.log" || true)"
}

for m in "${masses[@]}"; do
   run "k_theta_${m}" "$(mass_override "${m}")" \
      "&sweep y_values = 0.055, 0.0625, 0.070, 0.080, 0.0912, 0.105, 0.125, 0.150 /"
   run "rule_factor_${m}" "$(mass_override "${m}")" \
      "&sweep y_variable = '&stops rule_factor', y_values = 1.0, 1.5, 2.0, 3.0, 5.0, 10.0 /"
done
run paper_integrator "&sweep y_values = 0.0912 /" \
   "&solver method = 'newmark', step_control = 'half_step', half_step_tolerance = 0.01, stop_solution = 'fixed_point' /"

python3 "${root}/scripts/paper_regimes.py" "${out}" | tee "${out}/summary.md"
