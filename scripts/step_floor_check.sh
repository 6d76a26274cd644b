#!/usr/bin/env bash
# scripts/step_floor_check.sh - issue 10 item 2: "step below the minimum" never occurs on any
# deck in inputs/ at any tolerance >= 1e-9.
#
# Usage:
#   scripts/step_floor_check.sh [PERIODS]      (default 2 forcing periods per run, from rest)
#   GAPBEAM=/path/to/gapbeam scripts/step_floor_check.sh
#   DECKS="inputs/a.nml ..." METHODS="newmark rk45" TOLS="1e-9" STEP_FLOOR_OUT=bench_results/x.txt \
#      scripts/step_floor_check.sh        (a subset, into another file)
#
# Every deck of inputs/ that describes a forced beam (the transient decks, and the base model
# of the sweep decks run as a transient) is run with each error-controlled method
# (newmark, hht, generalized_alpha, rk45) at tolerance 1e-2, 1e-4, 1e-6 and 1e-9, and in two
# variants of its stop: with a contact damper of 0.001 N s/m and as a Hertz stop (1e-9 Hertz with
# Newmark and RK45 only). Each run covers PERIODS forcing periods from rest with the diagnostics
# off. A run passes when it exits 0; the table gives the steps taken and the CPU seconds. The
# check is a benchmark (release build, minutes), not a timed test.
# Output: bench_results/step_floor_check.txt; exit status 1 when any run failed.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "${root}"
periods=${1:-2}

if [[ -z ${GAPBEAM:-} ]]; then
   # shellcheck disable=SC1091
   source scripts/setup.sh >/dev/null
   fpm build --profile release >/dev/null
   # fpm prints the executable's path with `--runner echo`; other lines are skipped
   while IFS= read -r line; do
      if [[ -f ${line} && -x ${line} ]]; then GAPBEAM=${line}; fi
   done < <(fpm run --profile release --runner echo gapbeam 2>/dev/null)
fi
mkdir -p bench_results
tmp=$(mktemp -d)
trap 'rm -rf "${tmp}"' EXIT
out=${STEP_FLOOR_OUT:-bench_results/step_floor_check.txt}
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1

# DECKS="a.nml b.nml" runs only those
read -r -a decks <<< "${DECKS:-}"
[[ ${#decks[@]} -gt 0 ]] || decks=(inputs/moon_shaw_10p5hz.nml inputs/moon_shaw_10p2hz.nml inputs/moon_shaw_9p8hz.nml
       inputs/moon_shaw_10p5hz_3el.nml inputs/moon_shaw_9p8hz_3el.nml
       inputs/moon_shaw_10p5hz_15el.nml inputs/sweep_line_4mm.nml inputs/sweep_grid_gap.nml
       inputs/continuation_gap.nml
       inputs/tube_multispan.nml)
# a deck missing from this checkout is skipped
for i in "${!decks[@]}"; do [[ -f ${decks[i]} ]] || unset 'decks[i]'; done
read -r -a methods <<< "${METHODS:-newmark hht generalized_alpha rk45}"
read -r -a tols <<< "${TOLS:-1e-2 1e-4 1e-6 1e-9}"
variants=(as_given damper hertz)

n_run=0; n_fail=0
{
   echo "step_floor_check: ${periods} forcing periods from rest per run; $(${GAPBEAM} --version | head -1)"
   printf '%-34s %-8s %-18s %-6s %-6s %10s %9s  %s\n' deck variant method tol status steps cpu_s message
} | tee "${out}"
for deck in "${decks[@]}"; do
   # a tube deck (two planes, ring supports) runs as given (its supports are rings, which the
   # damper and Hertz variants of a flat stop do not describe)
   # and under Newmark alone: the other methods refuse ring supports with a message naming it
   deck_variants=("${variants[@]}")
   deck_methods=("${methods[@]}")
   if grep -qiE 'planes *= *2' "${deck}"; then deck_variants=(as_given); deck_methods=(newmark); fi
   for variant in "${deck_variants[@]}"; do
      # a continuation deck's exact monodromy needs the exact integrator; as a transient
      # run by other methods it asks for none
      copt=()
      if grep -q '&continuation' "${deck}"; then
         copt=("&continuation jacobian = 'finite_difference' /")
      fi
      case ${variant} in
         as_given) vopt="&stops /" ;;
         damper) vopt="&stops damping = 0.001 /" ;;
         hertz) vopt="&stops law = 'hertz' /" ;;
      esac
      for method in "${deck_methods[@]}"; do
         for tol in "${tols[@]}"; do
            # generalized-alpha and HHT at the Hertz stop are covered by Newmark's error control;
            # a 15-element RK45 run is stiffness-limited (minutes) and adds nothing at 1e-2..1e-6
            if [[ ${variant} == hertz && ( ${method} == hht || ${method} == generalized_alpha ) ]]; then
               continue
            fi
            n_run=$((n_run + 1))
            log=${tmp}/run.log
            set +e
            "${GAPBEAM}" "${deck}" --quiet "&job analysis = 'transient', output = '${tmp}/r' /" \
               "${vopt}" "${copt[@]}" \
               "&solver method = '${method}', step_control = 'error', tolerance = ${tol}, transient_periods = 0, record_periods = ${periods} /" \
               "&diagnostics lyapunov_periods = 0, settle_windows = 0, certify = .false. /" "&output history_periods = 0, write_text = .false. /" \
               > "${log}" 2>&1
            rc=$?
            set -e
            steps=$(grep -m1 -o 'steps[: ]*[0-9]*' "${log}" | grep -o '[0-9]*$' || true)
            cpu=$(grep -m1 -o '^cpu: [0-9.eE+-]*' "${log}" | cut -d' ' -f2 || true)
            msg=""
            if [[ ${rc} -ne 0 ]]; then
               n_fail=$((n_fail + 1))
               msg=$(grep -m1 -i 'error' "${log}" | cut -c1-160 || true)
            fi
            printf '%-34s %-8s %-18s %-6s %-6s %10s %9s  %s\n' "$(basename "${deck}")" "${variant}" \
               "${method}" "${tol}" "${rc}" "${steps:--}" "${cpu:--}" "${msg}" | tee -a "${out}"
         done
      done
   done
done
echo "${n_run} runs, ${n_fail} failed" | tee -a "${out}"
[[ ${n_fail} -eq 0 ]]
