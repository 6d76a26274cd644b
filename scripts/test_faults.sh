#!/usr/bin/env bash
# scripts/test_faults.sh - reproducers of known input-handling defects, through the real gapbeam
# executable; each case checks the DESIRED behaviour (so a case fails until its defect is fixed).
#
# Usage:
#   scripts/test_faults.sh GAPBEAM_EXE
#
# Every case runs in a fresh temporary directory (the working directory of the run), on a deck of
# inputs/ (or a copy of one, edited) with command-line overrides that make it cheap (2 + 4 forcing
# periods, a Lyapunov exponent over 2 periods, no sweep progress lines) and put the output prefix
# in that directory. The run gets a time limit (GAPBEAM_FAULTS_TIMEOUT, default 20 s; some cases
# less) and an address-space limit of 1 GiB (`ulimit -v`), OMP_NUM_THREADS=1.
#
# Checks:
#   clean error  exit status 1; stderr is exactly one line, starting `error: `, naming the deck
#                path as given, the group `&GROUP` and each expected word (variable names); no
#                `ERROR STOP`, `Backtrace`, `Fortran runtime`, `At line`; no file but the deck
#                (and copies of it) left in the case directory.
#   ok           exit status 0; PREFIX.h5 exists; nothing like a runtime error or warning on
#                stderr (`At line`, `Fortran runtime`, `ERROR STOP`, `Backtrace`).
#   (a few cases check something else; see each case)
# Prints `PASS  faults: <case>` or `FAIL  faults: <case> (<why>; stderr was: ...)` per case, then
# `test_faults.sh: N checks, M failed`; exit status 1 if any case failed.
set -uo pipefail

if [[ $# -ne 1 || ${1:-} == -h || ${1:-} == --help ]]; then
   printf 'usage: %s GAPBEAM_EXE\n' "$0" >&2
   exit 2
fi
exe=$1
if [[ ! -f ${exe} || ! -x ${exe} ]]; then
   printf "FAIL  faults: GAPBEAM_EXE '%s' is not an executable file\n" "${exe}"
   printf 'test_faults.sh: 1 checks, 1 failed\n'
   exit 1
fi
[[ ${exe} == /* ]] || exe=${PWD}/${exe}
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
inputs=${root}/inputs

top=$(mktemp -d "${TMPDIR:-/tmp}/gapbeam-faults-XXXXXX")
trap 'rm -rf "${top}"' EXIT
default_timeout=${GAPBEAM_FAULTS_TIMEOUT:-20}
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
unset GFORTRAN_ERROR_BACKTRACE

cheap=('&solver transient_periods=2, record_periods=4 /' '&diagnostics lyapunov_periods=2 /')
sweep_cheap=("${cheap[@]}" '&sweep progress=.false. /')

n_checks=0
n_failed=0
dir=''        # the current case's directory
status=0      # exit status of the last run (124: time-out)
seconds=0     # its wall time, whole seconds
deck=''       # deck path given to the last run

# Start a case: a fresh directory.
new_case() {
   dir=$(mktemp -d "${top}/case-XXXXXX")
   : >"${dir}/run.stderr"
   : >"${dir}/run.stdout"
}

# Copy inputs/$1 into the case directory and print the copy's path.
copy_deck() {
   cp "${inputs}/$1" "${dir}/$1"
   printf '%s' "${dir}/$1"
}

# run LIMIT_S DECK [ARG ...]: run the program in the case directory.
run() {
   local limit=$1 t0
   shift
   deck=$1
   t0=$(date +%s)
   status=0
   (cd "${dir}" && ulimit -v 1048576 && timeout --kill-after=5 "${limit}" "${exe}" "$@" \
      </dev/null >"${dir}/run.stdout" 2>"${dir}/run.stderr") || status=$?
   seconds=$(( $(date +%s) - t0 ))
}

# First 300 characters of stderr on one line.
stderr_line() {
   local s
   s=$(head -c 2000 "${dir}/run.stderr")
   s=${s//$'\n'/ | }
   [[ -n ${s} ]] || s='(empty)'
   if [[ ${#s} -gt 300 ]]; then s="${s:0:300} ..."; fi
   printf '%s' "${s}"
}

# report NAME [WHY ...]: PASS without WHY, else FAIL.
report() {
   local name=$1 why
   shift
   n_checks=$((n_checks + 1))
   if [[ $# -eq 0 ]]; then
      printf 'PASS  faults: %s\n' "${name}"
      return 0
   fi
   n_failed=$((n_failed + 1))
   why=$(printf '%s; ' "$@")
   printf 'FAIL  faults: %s (%sstderr was: %s)\n' "${name}" "${why}" "$(stderr_line)"
}

# Reasons (printed one a line) why stderr shows a crash, a runtime check or a backtrace.
crash_reasons() {
   local e
   e=$(<"${dir}/run.stderr")
   if [[ ${status} -eq 124 || ${status} -eq 137 ]]; then
      printf 'timed out (status %s)\n' "${status}"
   elif [[ ${status} -gt 128 ]]; then
      printf 'killed by signal %s\n' "$((status - 128))"
   fi
   if [[ ${e} == *'Fortran runtime'* || ${e} == *'At line '* ]]; then
      printf 'a Fortran runtime error or warning on stderr\n'
   fi
   if [[ ${e} == *'ERROR STOP'* || ${e} == *'Backtrace'* || ${e} == *'STOP '[0-9]* ]]; then
      printf 'ERROR STOP / backtrace on stderr\n'
   fi
   if [[ ${e} == *'floating-point exceptions are signalling'* ]]; then
      printf 'the IEEE exception note on stderr\n'
   fi
}

# Reasons why the last run is not a clean error naming &GROUP and each WORD.
clean_error_reasons() {
   local group=$1 first n w extra
   shift
   crash_reasons
   if [[ ${status} -eq 0 ]]; then
      printf 'exit status 0 (the run went through), want 1 and an error\n'
      return 0
   fi
   [[ ${status} -eq 1 ]] || printf 'exit status %s, want 1\n' "${status}"
   n=$(grep -c '' "${dir}/run.stderr")
   [[ ${n} -eq 1 ]] || printf 'stderr has %s lines, want 1\n' "${n}"
   first=$(head -n 1 "${dir}/run.stderr")
   [[ ${first} == 'error: '* ]] || printf "stderr does not start with 'error: '\n"
   [[ ${first} == *"${deck}"* ]] || printf 'the error does not name the deck\n'
   [[ ${first} == *"&${group}"* ]] || printf 'the error does not name &%s\n' "${group}"
   for w in "$@"; do
      [[ ${first} == *"${w}"* ]] || printf "the error does not name '%s'\n" "${w}"
   done
   extra=$(cd "${dir}" && find . -type f ! -name 'run.std*' ! -name '*.nml' | head -n 3 \
           | tr '\n' ' ')
   [[ -z ${extra} ]] || printf 'files left after the error: %s\n' "${extra}"
}

# Reasons why the last run is not a success that wrote PREFIX.h5.
ok_reasons() {
   local prefix=$1
   crash_reasons
   [[ ${status} -eq 0 ]] || printf 'exit status %s, want 0\n' "${status}"
   [[ -f ${prefix}.h5 ]] || printf 'no %s.h5\n' "${prefix##*/}"
}

# expect_clean_error NAME GROUP [WORD ...] (on the last run)
expect_clean_error() {
   local name=$1 why=()
   shift
   mapfile -t why < <(clean_error_reasons "$@")
   report "${name}" "${why[@]}"
}

# expect_ok NAME PREFIX (on the last run)
expect_ok() {
   local why=()
   mapfile -t why < <(ok_reasons "$2")
   report "$1" "${why[@]}"
}

out_override() { printf "&job output='%s' /" "${dir}/$1"; }

printf 'test_faults.sh: %s\n' "${exe}"

# ---- negative node numbers and list entries: -1 is the readers' "not given" marker -------------
new_case; run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" "$(out_override out)" \
   '&stops node=-1 /'
expect_clean_error '&stops node=-1 is an error (today: runs with no stop)' stops node

new_case; run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" "$(out_override out)" \
   '&stops node=5, -1 /'
expect_clean_error '&stops node=5, -1 is an error (today: entry 2 dropped)' stops node

new_case; run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" "$(out_override out)" \
   '&masses node=-1, mass=1.0 /'
expect_clean_error '&masses node=-1, mass=1.0 is an error (today: the mass is dropped)' masses node

new_case; run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" "$(out_override out)" \
   '&springs node=-1, stiffness=1.0e3 /'
expect_clean_error '&springs node=-1 is an error (today: the spring is dropped)' springs node

new_case; run "${default_timeout}" "${inputs}/sweep_line_4mm.nml" "$(out_override out)" \
   "${sweep_cheap[@]}" '&sweep n_frequency=0, frequency_hz=9.5, 10.0, -1 /'
expect_clean_error 'sweep frequency_hz list ending in -1 is an error (today: -1 dropped)' \
   sweep frequency_hz

new_case; run "${default_timeout}" "${inputs}/sweep_grid_gap.nml" "$(out_override out)" \
   "${sweep_cheap[@]}" '&sweep n_frequency=2, n_amplitude=0, amplitude_pp=1.0e-3, 2.0e-3, -1 /'
expect_clean_error 'sweep amplitude_pp list ending in -1 is an error (today: -1 dropped)' \
   sweep amplitude_pp

# ---- overflow -----------------------------------------------------------------------------------
new_case; run "${default_timeout}" "${inputs}/sweep_grid_gap.nml" "$(out_override out)" \
   "${sweep_cheap[@]}" '&sweep n_frequency=65536 n_amplitude=65536 /'
expect_clean_error 'sweep 65536 x 65536 points is an error (today: 0 points, exit 0)' \
   sweep n_frequency

new_case; run "${default_timeout}" "${inputs}/sweep_grid_gap.nml" "$(out_override out)" \
   "${sweep_cheap[@]}" '&sweep n_frequency=50000 n_amplitude=50000 /'
expect_clean_error 'sweep 50000 x 50000 points is an error (today: a negative count)' \
   sweep n_frequency

new_case; run 10 "${inputs}/sweep_grid_gap.nml" "$(out_override out)" \
   "${sweep_cheap[@]}" '&sweep n_frequency=100000000 /'
expect_clean_error 'sweep n_frequency=100000000: an error within 10 s and 1 GiB (today: 2.3 GB allocated)' \
   sweep n_frequency

new_case; run "${default_timeout}" "${inputs}/moon_shaw_10p5hz.nml" "$(out_override out)" \
   '&solver transient_periods=2147483647, record_periods=100000000, steps_per_period=100000000, max_halvings=40 /'
expect_clean_error 'transient_periods + record_periods overflow is an error (today: the 2**62 tick check passes)' \
   solver transient_periods

new_case; run "${default_timeout}" "${inputs}/moon_shaw_10p5hz.nml" "$(out_override out)" \
   '&solver record_periods=2147483647 /'
expect_clean_error 'record_periods=2147483647 is refused before any allocation' \
   solver record_periods

new_case; run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" "$(out_override out)" \
   '&beam thickness=1.0e308 /'
expect_clean_error '&beam thickness=1e308 (EI overflows) is an error naming it (today: dsygv info=8)' \
   beam thickness

# ---- lengths: fixed-length strings --------------------------------------------------------------
new_case
long=${dir}/long/$(printf 'd%.0s' {1..60})/$(printf 'd%.0s' {1..60})/$(printf 'd%.0s' {1..60})/$(printf 'r%.0s' {1..60})
run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" "&job output='${long}' /"
why=()
if [[ ${status} -eq 0 ]]; then
   mapfile -t why < <(ok_reasons "${long}")
   grep -qxF "output: ${long}" "${dir}/run.stdout" || why+=('stdout does not show the prefix whole')
else
   mapfile -t why < <(clean_error_reasons job output)
fi
report "&job output of ${#long} characters: used whole or refused (today: cut at 256, lands elsewhere)" \
   "${why[@]}"

new_case
title=$(printf 't%.0s' {1..300})
run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" "$(out_override out)" \
   "&job title='${title}' /"
why=()
if [[ ${status} -eq 0 ]]; then
   mapfile -t why < <(ok_reasons "${dir}/out")
   grep -qxF "gapbeam: ${title}" "${dir}/run.stdout" || why+=('the title is cut')
else
   mapfile -t why < <(clean_error_reasons job title)
fi
report '&job title of 300 characters: used whole or refused (today: cut at 256)' "${why[@]}"

new_case
pad=$(printf ' %.0s' {1..5000})
run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" "$(out_override out)" \
   "&job title='long override'${pad} /"
why=()
if [[ ${status} -eq 0 ]]; then
   mapfile -t why < <(ok_reasons "${dir}/out")
else
   mapfile -t why < <(clean_error_reasons job override)
   grep -q 'End of file' "${dir}/run.stderr" && why+=("the error says 'End of file'")
fi
report 'override of 5000+ characters: read whole or refused with its length (today: End of file)' \
   "${why[@]}"

# ---- empty values -------------------------------------------------------------------------------
new_case; run "${default_timeout}" "${inputs}/moon_shaw_10p5hz.nml" "$(out_override out)" \
   "${cheap[@]}" '&forcing frequency_hz = , /'
expect_clean_error '&forcing frequency_hz = , is an error (today: the deck value is kept)' \
   forcing frequency_hz

new_case; d=$(copy_deck moon_shaw_modes.nml)
sed -i 's/n_elem = 4 /n_elem = , /' "${d}"
run "${default_timeout}" "${d}" "$(out_override out)"
expect_clean_error 'n_elem = , in the deck file is an error (today: the default 4 is used)' \
   beam n_elem

# ---- line ends ----------------------------------------------------------------------------------
new_case; d=$(copy_deck moon_shaw_modes.nml)
tr '\n' '\r' <"${inputs}/moon_shaw_modes.nml" >"${d}"
run "${default_timeout}" "${d}" "$(out_override out)"
expect_ok 'CR-only line ends run like LF (today: required group &job is missing)' "${dir}/out"

new_case; d=$(copy_deck moon_shaw_modes.nml)
sed 's/$/\r/' "${inputs}/moon_shaw_modes.nml" >"${d}"
run "${default_timeout}" "${d}" "$(out_override out)"
expect_ok 'CRLF line ends run like LF' "${dir}/out"

new_case; d=$(copy_deck moon_shaw_modes.nml)
{ printf '\xef\xbb\xbf'; cat "${inputs}/moon_shaw_modes.nml"; } >"${d}"
run "${default_timeout}" "${d}" "$(out_override out)"
expect_ok 'a UTF-8 byte-order mark is ignored' "${dir}/out"

# ---- exit paths: one error line, the documented status, no backtrace ----------------------------
new_case; run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" "$(out_override out)" \
   '&beam length=-1 /'
expect_clean_error '&beam length=-1: one error line, exit 1, no backtrace' beam length

new_case; run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" "$(out_override out)" \
   '&beam length=NaN /'
expect_clean_error '&beam length=NaN: one error line (no IEEE note), exit 1, no backtrace' \
   beam length

new_case; deck=''; status=0
(cd "${dir}" && timeout 10 "${exe}" </dev/null >"${dir}/run.stdout" 2>"${dir}/run.stderr") \
   || status=$?
mapfile -t why < <(crash_reasons)
[[ ${status} -eq 2 ]] || why+=("exit status ${status}, want 2")
grep -q '^usage: gapbeam' "${dir}/run.stderr" || why+=('no usage line')
report 'no argument: usage on stderr, exit 2, no ERROR STOP or backtrace' "${why[@]}"

new_case; run "${default_timeout}" "${inputs}/sweep_grid_gap.nml" "$(out_override out)" \
   "${sweep_cheap[@]}" '&sweep n_frequency=4, n_amplitude=1, chunk=1 /' --time-limit 0.000001
mapfile -t why < <(crash_reasons)
[[ ${status} -eq 3 ]] || why+=("exit status ${status}, want 3")
[[ -f ${dir}/out.checkpoint ]] || why+=('no checkpoint kept')
[[ ! -s ${dir}/run.stderr ]] || why+=('stderr not empty')
report '--time-limit reached: exit 3, checkpoint kept, nothing on stderr' "${why[@]}"

# ---- more defects found by scripts/fuzz_decks.py ------------------------------------------------
new_case; run "${default_timeout}" "${inputs}/sweep_line_4mm.nml" "$(out_override new/sub/out)" \
   "${sweep_cheap[@]}" '&sweep n_frequency=3 /'
expect_ok 'a sweep into a missing directory (today: the checkpoint cannot be created)' \
   "${dir}/new/sub/out"

new_case; run "${default_timeout}" "${inputs}/model_size_10p5hz.nml" "$(out_override out)" \
   "${cheap[@]}" '&model_size elements=2, 3, modes=1 /'
why=()
grep -q '^model size: 2 meshes and 2 modal models' "${dir}/run.stdout" \
   || why+=("stdout: '$(grep '^model size' "${dir}/run.stdout")', want 2 meshes and 2 modal models")
mapfile -t more < <(ok_reasons "${dir}/out")
report '&model_size elements=2, 3, modes=1 runs that ladder (today: the default tail is kept)' \
   "${why[@]}" "${more[@]}"

new_case; run 10 "${inputs}/moon_shaw_10p5hz.nml" "$(out_override out)" "${cheap[@]}" \
   "&solver method='exact' /" '&forcing amplitude_pp=0 /'
expect_ok "method='exact' from rest without forcing ends within 10 s (today: hangs)" "${dir}/out"

new_case; run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" "$(out_override out)" \
   '&stops rule_f1_ratio=NaN /'
expect_clean_error '&stops rule_f1_ratio=NaN is an error naming it (today: rule_f1_hz(1) = 0 is blamed)' \
   stops rule_f1_ratio

printf 'test_faults.sh: %d checks, %d failed\n' "${n_checks}" "${n_failed}"
[[ ${n_failed} -eq 0 ]]
