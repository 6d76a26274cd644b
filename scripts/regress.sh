#!/usr/bin/env bash
# scripts/regress.sh - regression runs for a refactor: run every deck (reduced sizes) before and
# after, and compare the outputs (bitwise, or to a stated relative tolerance).
#
# Usage:
#   scripts/regress.sh run OUTDIR [GAPBEAM_EXE]
#   scripts/regress.sh compare DIR_A DIR_B [--rtol X] [--atol X] [--no-logs] [--quiet]
#   scripts/regress.sh list                     (the cases and their command lines)
#   scripts/regress.sh -h | --help
#
# run: without GAPBEAM_EXE, builds the release profile (`fpm build --profile release`, quiet on
# success) and finds the executable with `fpm run --profile release --runner echo gapbeam`.
# OUTDIR must not exist or be empty (a leftover sweep checkpoint would be resumed). Every case
# runs from the repository root with a relative deck path, OPENBLAS_NUM_THREADS=1 and
# OMP_NUM_THREADS=1 (2 for the sweeps, whose results do not depend on the thread count), and
# writes its results with `&job output='OUTDIR/<case>'`; its standard output goes to
# OUTDIR/<case>.log, with a last line `# regress: exit status N`, its standard error to
# OUTDIR/<case>.err. OUTDIR/_cases.txt lists the command lines, OUTDIR/_times.txt the wall time
# and exit status of each case and the total, OUTDIR/_meta.txt the commit and the executable.
# The cases (see `list`; 60): every deck in inputs/ and the runnable test/decks/*.nml, with short
# horizons where a deck is long (10 discarded + 16 recorded periods, 8 Lyapunov periods, 4 history
# periods for transient runs, model-size ladders and sweep points; fewer study levels, rungs and
# sweep points), so that a chaotic response cannot blow a round-off difference up to O(1) and a
# relative tolerance stays meaningful; every integrator on the 10.5 Hz deck (Newmark half-step,
# fixed, without events, linear acceleration, fixed point, the paper's method, HHT, generalized-
# alpha, central difference, RK4, RK45, exact); modal reduction, the output filter, the banded
# solver, consistent mass, two-sided stops with and without a contact damper, a Hertz stop;
# sweeps independent (2 threads), continuation up, down and along the amplitude, two shards and
# their merge; four error cases that exit 1 (`e_*`: a divergence, and HHT, generalized-alpha and
# a contact damper with half-step control, which stop with "step below the minimum" in a545dd7).
# About 10 s on 2 cores.
# GAPBEAM_REGRESS_LONG=1 adds the transient decks at their full horizon (bitwise checks only:
# over 1300 periods of a chaotic response any change of operation order grows to O(1)).
# Exit status of run: 0 when every case ran (a case's own exit status is recorded, not judged:
# compare judges it); 1 when the build fails or OUTDIR is not empty.
#
# compare: python3 scripts/regress_compare.py DIR_A DIR_B [options]: every .h5 dataset, every
# .dat/.txt table (numeric tokens) and every .log/.err (exit status, masked timings) of A against
# B, timing fields ignored; one line per file and a summary; exit 0 when everything is bitwise
# identical or within --rtol (default 0), 1 otherwise. See `python3 scripts/regress_compare.py -h`.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "${root}"

usage() {
   sed -n '2,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' scripts/regress.sh
}

# ---------------------------------------------------------------------------------------------
# The cases. add NAME THREADS DECK [ARG ...]: ARGs are passed verbatim after DECK (overrides,
# --shard); @OUT@ in an ARG is replaced by OUTDIR. `&job output='OUTDIR/NAME' /` is appended.
# DECK 'merge' runs `gapbeam merge ARG ...` instead (no output override).
# ---------------------------------------------------------------------------------------------
case_names=()
case_threads=()
case_decks=()
case_args=()
sep=$'\x1f'

add() {
   local name=$1 threads=$2 deck=$3
   shift 3
   local joined="" a
   for a in "$@"; do joined+="${a}${sep}"; done
   case_names+=("${name}")
   case_threads+=("${threads}")
   case_decks+=("${deck}")
   case_args+=("${joined}")
}

# Short horizons for transient-type runs (each group may appear once per override, and a later
# override replaces what an earlier one set, so a variant's own &solver comes after these).
short_solver='&solver transient_periods = 10, record_periods = 16 /'
short_diag='&diagnostics lyapunov_periods = 8 /'
short_output='&output history_periods = 4 /'
short=("${short_solver}" "${short_diag}" "${short_output}")

define_cases() {
   local d
   # --- inputs/: modes and calibration (already short: full size)
   add moon_shaw_modes 1 inputs/moon_shaw_modes.nml
   add derive_thickness 1 inputs/derive_thickness.nml
   add derive_width 1 inputs/derive_width.nml

   # --- inputs/: transient decks, short horizons
   for d in moon_shaw_10p5hz moon_shaw_10p2hz moon_shaw_9p8hz moon_shaw_10p5hz_15el \
            moon_shaw_10p5hz_3el moon_shaw_9p8hz_3el; do
      add "${d}" 1 "inputs/${d}.nml" "${short[@]}"
   done

   # --- every integrator on the 10.5 Hz deck (deck: newmark, condensed, half_step, events)
   local m=inputs/moon_shaw_10p5hz.nml
   # the methods that need a mass at every dof (explicit, conditionally stable Newmark) run on
   # the former reference model (rigid-half-element rotary inertia); the deck's rotations are
   # massless
   local h=test/decks/moon_shaw_10p5hz_half_element.nml
   local h15=("&beam n_elem = 15 /" "&stops node = 16 /")
   add i_newmark_fixed 1 "${m}" "${short[@]}" "&solver step_control = 'fixed' /"
   add i_newmark_fixed_no_events 1 "${m}" "${short[@]}" \
      "&solver step_control = 'fixed', locate_events = .false. /"
   add i_linear_acceleration 1 "${h}" "${short[@]}" \
      "&solver step_control = 'fixed', newmark_alpha = 0.16666666666666666 /"
   add i_fixed_point 1 "${m}" "${short[@]}" "&solver stop_solution = 'fixed_point' /"
   add i_paper 1 "${m}" "${short[@]}" \
      "&solver stop_solution = 'fixed_point', locate_events = .false. /"
   add i_hht 1 "${m}" "${short[@]}" \
      "&solver method = 'hht', hht_alpha = -0.1, step_control = 'fixed' /"
   add i_generalized_alpha 1 "${m}" "${short[@]}" \
      "&solver method = 'generalized_alpha', rho_infinity = 0.6, step_control = 'fixed' /"
   # HHT and generalized-alpha with the deck's half-step control stop at t = 0 with "step below
   # the minimum" (the residual ratio does not fall with dt) in a545dd7: kept as error cases
   add e_hht_half_step 1 "${m}" "${short[@]}" "&solver method = 'hht' /"
   add e_generalized_alpha_half_step 1 "${m}" "${short[@]}" \
      "&solver method = 'generalized_alpha' /"
   # omega_max dt = 2007 rad/s x T/256 = 0.75 < 2: stable
   add i_central_difference 1 "${h}" "${short[@]}" \
      "&solver method = 'central_difference', step_control = 'fixed' /"
   add i_rk4 1 "${h}" "${short[@]}" "&solver method = 'rk4', step_control = 'fixed' /"
   add i_rk45 1 "${h}" "${short[@]}" \
      "&solver method = 'rk45', step_control = 'embedded', rk_rtol = 1.0e-7 /"
   add i_exact 1 "${m}" "${short[@]}" "&solver method = 'exact' /"
   add i_exact_15el 1 inputs/moon_shaw_10p5hz_15el.nml "${short[@]}" "&solver method = 'exact' /"

   # --- model variants on the 10.5 Hz deck
   add v_modal 1 "${m}" "${short[@]}" "&reduction kind = 'modal', n_modes = 3 /"
   add v_modal_no_static 1 "${m}" "${short[@]}" \
      "&reduction kind = 'modal', n_modes = 4, static_correction = .false. /"
   add v_modal_15el_rk4 1 inputs/moon_shaw_10p5hz_15el.nml "${short[@]}" \
      "&reduction kind = 'modal', n_modes = 4 /" \
      "&solver method = 'rk4', step_control = 'fixed' /"
   add v_filter 1 "${m}" "${short[@]}" \
      "&output filter_cutoff_hz = 40.0, poincare_phase_deg = 90.0 /"
   add v_banded_15el 1 inputs/moon_shaw_10p5hz_15el.nml "${short[@]}" \
      "&solver linear_solver = 'banded' /"
   add v_consistent 1 "${m}" "${short[@]}" "&beam mass_matrix = 'consistent' /"
   add v_two_sided 1 "${m}" "${short[@]}" "&stops side = 'both', gap = 0.5e-3 /"
   add v_two_sided_exact 1 "${m}" "${short[@]}" "&stops side = 'both', gap = 0.5e-3 /" \
      "&solver method = 'exact' /"
   add v_two_sided_damper 1 "${m}" "${short[@]}" \
      "&stops side = 'both', gap = 0.5e-3, damping = 0.02 /" "&solver step_control = 'fixed' /"
   add v_two_sided_damper_hht 1 "${m}" "${short[@]}" \
      "&stops side = 'both', gap = 0.5e-3, damping = 0.02 /" \
      "&solver method = 'hht', step_control = 'fixed' /"
   add v_two_sided_damper_rk45 1 "${h}" "${short[@]}" \
      "&stops side = 'both', gap = 0.5e-3, damping = 0.02 /" \
      "&solver method = 'rk45', step_control = 'embedded' /"
   # a contact damper with the half-step control stops at the first contact with "step below
   # the minimum" in a545dd7: kept as an error case
   add e_damper_half_step 1 "${m}" "${short[@]}" \
      "&stops side = 'both', gap = 0.5e-3, damping = 0.02 /"
   add v_hertz 1 "${m}" "${short[@]}" \
      "&stops law = 'hertz', stiffness = 3.0e3, exponent = 1.5, rule_factor = 0.0 /"
   add v_hertz_rk45 1 "${h}" "${short[@]}" \
      "&stops law = 'hertz', stiffness = 3.0e3, exponent = 1.5, rule_factor = 0.0 /" \
      "&solver method = 'rk45', step_control = 'embedded' /"
   # an error path: central difference far beyond its stable step diverges (exit status 1)
   add e_diverges 1 "${h}" "${h15[@]}" "${short[@]}" \
      "&solver method = 'central_difference', step_control = 'fixed' /"

   # --- inputs/: studies (fewer levels, rungs and periods)
   add stability_4el 1 inputs/stability_4el.nml
   add stability_15el 1 inputs/stability_15el.nml
   add work_precision_4el 1 inputs/work_precision_4el.nml "&study levels = 4, repeats = 1 /"
   add work_precision_15el 1 inputs/work_precision_15el.nml \
      "&study levels = 3, repeats = 1, periods = 5 /"
   add work_precision_linear 1 inputs/work_precision_linear.nml "&study levels = 4, repeats = 1 /"
   # distinct coordinate counts (5, 9, 17 | 1, 2, 3, 4): the recommendation never falls to the
   # tie-break on run time
   add model_size_10p5hz 1 inputs/model_size_10p5hz.nml "${short_solver}" "${short_diag}" \
      "&model_size elements = 2, 4, 8, 0, 0, 0, 0, modes = 1, 3, 0, 0, 0, 0 /"
   add model_size_9p8hz 1 inputs/model_size_9p8hz.nml "${short_solver}" "${short_diag}" \
      "&model_size elements = 2, 4, 8, 0, 0, 0, 0, modes = 1, 3, 0, 0, 0, 0 /"
   add model_size_9p8hz_40hz 1 inputs/model_size_9p8hz.nml "${short_solver}" "${short_diag}" \
      "&model_size elements = 2, 4, 8, 0, 0, 0, 0, modes = 1, 3, 0, 0, 0, 0 /" \
      "&output filter_cutoff_hz = 40.0 /"

   # --- inputs/: sweeps (few points, short horizons, no progress lines)
   local sw='&sweep progress = .false. /'
   add sweep_line_4mm 2 inputs/sweep_line_4mm.nml "${short_solver}" "${short_diag}" \
      "&sweep n_frequency = 7, progress = .false. /"
   add sweep_line_4mm_down 2 inputs/sweep_line_4mm.nml "${short_solver}" "${short_diag}" \
      "&sweep n_frequency = 7, direction = 'down', progress = .false. /"
   add sweep_line_4mm_amplitude 2 inputs/sweep_line_4mm.nml "${short_solver}" "${short_diag}" \
      "&sweep n_frequency = 2, axis = 'amplitude', amplitude_pp = 2.0e-3, 3.0e-3, 4.0e-3, progress = .false. /"
   add sweep_grid_gap 2 inputs/sweep_grid_gap.nml "${short_solver}" "${short_diag}" \
      "&sweep n_frequency = 4, n_amplitude = 3, progress = .false. /"
   add sweep_grid_gap_shards 1 inputs/sweep_grid_gap.nml "${short_solver}" "${short_diag}" \
      "&sweep n_frequency = 4, n_amplitude = 3, progress = .false. /" --shard 1/2
   add sweep_grid_gap_shards 1 inputs/sweep_grid_gap.nml "${short_solver}" "${short_diag}" \
      "&sweep n_frequency = 4, n_amplitude = 3, progress = .false. /" --shard 2/2
   add sweep_grid_gap_merged 1 merge '@OUT@/sweep_grid_gap_merged' \
      '@OUT@/sweep_grid_gap_shards.shard_1_of_2.h5' '@OUT@/sweep_grid_gap_shards.shard_2_of_2.h5'

   # --- test/decks/: the runnable ones (input_full has a two-sided stop with a damper, a Hertz
   # stop, the fixed point and the banded solver)
   add t_exact_free_beam 1 test/decks/exact_free_beam.nml \
      '&solver record_periods = 20 /' '&diagnostics lyapunov_periods = 8 /'
   add t_exact_free_beam_exact 1 test/decks/exact_free_beam.nml \
      "&solver record_periods = 20, method = 'exact' /" '&diagnostics lyapunov_periods = 8 /'
   add t_input_full 1 test/decks/input_full.nml '&diagnostics lyapunov_periods = 8 /'
   add t_input_minimal 1 test/decks/input_minimal.nml
   add t_input_quotes 1 test/decks/input_quotes.nml
   add t_sdof_bilinear 1 test/decks/sdof_bilinear.nml '&diagnostics lyapunov_periods = 8 /'
   add t_sweep_small 2 test/decks/sweep_small.nml "${sw}"

   # --- optional: full horizons (bitwise checks only)
   if [[ ${GAPBEAM_REGRESS_LONG:-0} == 1 ]]; then
      for d in moon_shaw_10p5hz moon_shaw_9p8hz moon_shaw_10p5hz_15el; do
         add "long_${d}" 1 "inputs/${d}.nml"
      done
   fi
}

# The argument list of case $1 (index), with @OUT@ replaced by $2, into the array `args`.
case_argv() {
   local i=$1 out=$2 a
   args=()
   local rest=${case_args[i]}
   while [[ -n ${rest} ]]; do
      a=${rest%%"${sep}"*}
      rest=${rest#*"${sep}"}
      args+=("${a//@OUT@/${out}}")
   done
   if [[ ${case_decks[i]} != merge ]]; then
      args+=("&job output = '${out}/${case_names[i]}' /")
   fi
}

# Print a command line with each word quoted as needed.
print_cmd() {
   local w line=""
   for w in "$@"; do
      if [[ ${w} =~ ^[A-Za-z0-9_./=@:-]+$ ]]; then line+="${w} "; else line+="\"${w}\" "; fi
   done
   printf '%s\n' "${line% }"
}

cmd_list() {
   local i
   define_cases
   for i in "${!case_names[@]}"; do
      case_argv "${i}" OUTDIR
      printf '%-28s OMP_NUM_THREADS=%s ' "${case_names[i]}" "${case_threads[i]}"
      if [[ ${case_decks[i]} == merge ]]; then
         print_cmd gapbeam merge "${args[@]}"
      else
         print_cmd gapbeam "${case_decks[i]}" "${args[@]}"
      fi
   done
}

# Build the release profile and print the gapbeam executable's path.
build_release() {
   local build_log line exe=""
   # shellcheck source=setup.sh
   source "${root}/scripts/setup.sh" >&2 || return 1   # stdout carries the path only
   build_log=$(mktemp "${TMPDIR:-/tmp}/gapbeam-build-release-XXXXXX")
   printf '%s\n' "regress: fpm build --profile release (in ${root})" >"${build_log}"
   if ! fpm build --profile release >>"${build_log}" 2>&1; then
      cat "${build_log}" >&2
      printf 'regress: error: the release build failed (log %s)\n' "${build_log}" >&2
      return 1
   fi
   while IFS= read -r line; do
      [[ ${line} == /* ]] || line=${root}/${line}
      if [[ -f ${line} && -x ${line} ]]; then exe=${line}; fi
   done < <(fpm run --profile release --runner echo gapbeam 2>>"${build_log}")
   if [[ -z ${exe} ]]; then
      cat "${build_log}" >&2
      printf 'regress: error: cannot find the gapbeam executable (log %s)\n' "${build_log}" >&2
      return 1
   fi
   rm -f "${build_log}"
   printf '%s\n' "${exe}"
}

cmd_run() {
   [[ $# -ge 1 && $# -le 2 ]] || { usage >&2; exit 2; }
   local out exe i status t0 t1 t_all0 t_all1 dt log err n_fail=0
   out=$(realpath -m -- "$1")
   if [[ -d ${out} && -n $(ls -A -- "${out}") ]]; then
      printf 'regress: error: %s is not empty (a sweep would resume from its checkpoint)\n' \
         "${out}" >&2
      exit 1
   fi
   mkdir -p -- "${out}"
   if [[ $# -eq 2 ]]; then
      exe=$(realpath -- "$2")
      [[ -x ${exe} ]] || { printf 'regress: error: %s is not executable\n' "$2" >&2; exit 1; }
   else
      exe=$(build_release) || exit 1
   fi
   define_cases
   export OPENBLAS_NUM_THREADS=1
   # no backtrace (addresses change from run to run) after an error stop
   export GFORTRAN_ERROR_BACKTRACE=0
   {
      printf 'executable: %s\n' "${exe}"
      printf 'outdir: %s\n' "${out}"
      printf 'repository: %s\n' "${root}"
      printf 'commit: %s%s\n' "$(git -C "${root}" rev-parse HEAD 2>/dev/null || echo unknown)" \
         "$(git -C "${root}" diff --quiet HEAD -- src app 2>/dev/null || echo ' (+ uncommitted changes)')"
      printf 'last commit of src/ app/ bench/ fpm.toml: %s\n' \
         "$(git -C "${root}" log -1 --format='%h %s' -- src app bench fpm.toml 2>/dev/null || echo unknown)"
      printf 'date: %s\n' "$(date -u +%Y-%m-%dT%H:%M:%SZ)"
      printf 'host: %s, %s cores\n' "$(hostname)" "$(nproc)"
   } >"${out}/_meta.txt"
   : >"${out}/_cases.txt"
   printf '%-28s %8s %6s\n' case 'wall[s]' status >"${out}/_times.txt"
   printf 'regress: %d cases, executable %s, results in %s\n' "${#case_names[@]}" "${exe}" "${out}"
   t_all0=$(date +%s.%N)
   for i in "${!case_names[@]}"; do
      case_argv "${i}" "${out}"
      log=${out}/${case_names[i]}.log
      err=${out}/${case_names[i]}.err
      # the shards of one case share its name: their logs get the shard's suffix
      if [[ ${case_args[i]} == *--shard${sep}* ]]; then
         local shard=${case_args[i]##*--shard"${sep}"}
         shard=${shard%%"${sep}"*}
         log=${out}/${case_names[i]}.shard_${shard/\//_of_}.log
         err=${log%.log}.err
      fi
      if [[ ${case_decks[i]} == merge ]]; then
         cmd=("${exe}" merge "${args[@]}")
      else
         cmd=("${exe}" "${case_decks[i]}" "${args[@]}")
      fi
      { printf '%-28s OMP_NUM_THREADS=%s ' "${case_names[i]}" "${case_threads[i]}"
        print_cmd "${cmd[@]}"; } >>"${out}/_cases.txt"
      t0=$(date +%s.%N)
      status=0
      OMP_NUM_THREADS=${case_threads[i]} timeout 600 "${cmd[@]}" >"${log}" 2>"${err}" \
         || status=$?
      t1=$(date +%s.%N)
      printf '# regress: exit status %d\n' "${status}" >>"${log}"
      dt=$(awk -v a="${t0}" -v b="${t1}" 'BEGIN {printf "%.2f", b - a}')
      printf '%-28s %8s %6d\n' "${case_names[i]}" "${dt}" "${status}" >>"${out}/_times.txt"
      printf '  %-28s %6s s  exit %d\n' "${case_names[i]}" "${dt}" "${status}"
      [[ ${status} -eq 0 ]] || n_fail=$((n_fail + 1))
   done
   t_all1=$(date +%s.%N)
   dt=$(awk -v a="${t_all0}" -v b="${t_all1}" 'BEGIN {printf "%.1f", b - a}')
   printf '%-28s %8s\n' total "${dt}" >>"${out}/_times.txt"
   printf 'regress: %d cases in %s s, %d with a non-zero exit status (recorded in the logs)\n' \
      "${#case_names[@]}" "${dt}" "${n_fail}"
}

mode=${1:-}
case ${mode} in
   run) shift; cmd_run "$@" ;;
   compare) shift; exec python3 "${root}/scripts/regress_compare.py" "$@" ;;
   list) cmd_list ;;
   -h | --help) usage ;;
   *) usage >&2; exit 2 ;;
esac
