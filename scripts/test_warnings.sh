#!/usr/bin/env bash
# scripts/test_warnings.sh - warnings and the checks made before a run, through the real gapbeam
# executable (docs/running.md, "Warnings"):
#   - a gap of 2 m on the 0.2 m reference beam: the scale and reach warnings and the warning
#     about a stop never touched, each one line on standard error starting 'gapbeam:
#     warning: ', the same lines in /run/warnings of the file (h5py), the label's evidence;
#     the reference deck as shipped: no warning, /run/warnings empty;
#   - a long run (record_periods = 1e8) announced within seconds, before it gets far;
#   - a control character in a value is escaped on both streams, never written raw;
#   - an output name too long for the file system once gapbeam's suffixes are added: refused
#     at the start, before the computation.
# Usage: scripts/test_warnings.sh GAPBEAM_EXE   (scripts/test.sh calls it with the debug build)
# Prints `PASS  warnings: <case>` or `FAIL  warnings: <case> (<why>)` per check, then
# `test_warnings.sh: N checks, M failed`; exit status 1 if any check failed.
set -uo pipefail

if [[ $# -ne 1 ]]; then
   printf 'usage: %s GAPBEAM_EXE\n' "$0" >&2
   exit 2
fi
exe=$1
[[ ${exe} == /* ]] || exe=${PWD}/${exe}
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
deck=${root}/inputs/moon_shaw_10p5hz.nml
work=$(mktemp -d "${TMPDIR:-/tmp}/gapbeam-warnings-XXXXXX")
trap 'rm -rf "${work}"' EXIT
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
n_checks=0
n_failed=0
cheap=('&solver transient_periods = 10, record_periods = 20 /' '&diagnostics lyapunov_periods = 0 /')

check() {   # check NAME OK [WHY]
   n_checks=$((n_checks + 1))
   if [[ $2 == 1 ]]; then
      printf 'PASS  warnings: %s\n' "$1"
   else
      n_failed=$((n_failed + 1))
      printf 'FAIL  warnings: %s (%s)\n' "$1" "${3:-}"
   fi
}

# run NAME TIMEOUT ARGS...: run in the work directory; sets status, out and err
run() {
   local name=$1 limit=$2
   shift 2
   status=0
   (cd "${work}" && timeout -s TERM "${limit}" "${exe}" "$@" >"${name}.out" 2>"${name}.err") \
      || status=$?
   out=$(<"${work}/${name}.out")
   err=$(<"${work}/${name}.err")
}

# /run/warnings of FILE, one line each
stored() {
   python3 -c 'import sys, h5py
with h5py.File(sys.argv[1], "r") as f:
    for w in f["/run/warnings"][()]:
        print(w.decode() if isinstance(w, bytes) else w)' "$1"
}

# ---- the reference deck as shipped: quiet ---------------------------------------------------
run ref 120 "${deck}" "${cheap[@]}" "&job output = 'ref' /"
check 'the reference deck: exit 0, no warning on standard error' \
   "$([[ ${status} -eq 0 && ${err} != *warning* ]] && echo 1)" "status ${status}: ${err}"
check 'the reference deck: /run/warnings empty' \
   "$([[ -f ${work}/ref.h5 && -z $(stored "${work}/ref.h5") ]] && echo 1)" "$(stored "${work}/ref.h5")"

# ---- a gap of 2 m on a 0.2 m beam --------------------------------------------------------------
run gap 120 "${deck}" "${cheap[@]}" "&job output = 'gap' /" '&stops gap = 2.0 /'
mapfile -t lines < <(grep '^gapbeam: warning: ' "${work}/gap.err" | sed 's/^gapbeam: warning: //')
check 'gap 2 m: exit 0 (a warning does not stop a run)' "$([[ ${status} -eq 0 ]] && echo 1)" \
   "status ${status}: ${err}"
check 'gap 2 m: the scale warning names the gap and the span' \
   "$([[ ${err} == *'stop 1 (&stops gap(1) = 2 m) is 10 times the span L = 0.2 m'* ]] && echo 1)" \
   "${err}"
check 'gap 2 m: out of reach' "$([[ ${err} == *'gap 2 m is out of reach'* ]] && echo 1)" "${err}"
check 'gap 2 m: the stop was never touched in the record' \
   "$([[ ${err} == *'stop 1 was never touched in the 20 recorded periods'* ]] && echo 1)" "${err}"
check 'gap 2 m: every line of standard error is a warning (one line each)' \
   "$([[ ${#lines[@]} -eq 3 && $(wc -l <"${work}/gap.err") -eq 3 ]] && echo 1)" "${err}"
check 'gap 2 m: /run/warnings holds the same lines' \
   "$([[ $(stored "${work}/gap.h5") == "$(printf '%s\n' "${lines[@]}")" ]] && echo 1)" \
   "$(stored "${work}/gap.h5")"
check "gap 2 m: the label's evidence says the stop was never met" \
   "$([[ ${out} == *'stop 1 never met in the record (0 impacts)'* ]] && echo 1)" "${out}"

# ---- a long run announced ------------------------------------------------------------------------
run long 12 "${deck}" "&job output = 'long' /" '&solver record_periods = 100000000 /' --quiet
check 'record_periods = 1e8: a warning with the estimate within seconds (--quiet)' \
   "$([[ ${status} -eq 124 && ${err} == *'gapbeam: warning: this transient run will take about '*' more (h:mm:ss'* ]] && echo 1)" \
   "status ${status}: ${err}"

# ---- a control character in a value ---------------------------------------------------------------
esc=$'\033'
run ctl 60 "${root}/inputs/moon_shaw_modes.nml" "&job output = 'ctl', title = 'a${esc}[31mred' /"
check 'a control character in the title: escaped on standard output, never raw' \
   "$([[ ${status} -eq 0 && ${out} == *'a\x1b[31mred'* && ${out} != *${esc}* ]] && echo 1)" \
   "status ${status}: ${out}"
run ctl2 60 "${root}/inputs/moon_shaw_modes.nml" "&job analysis = 'mo${esc}des' /"
check 'a control character in a refused value: escaped in the error line' \
   "$([[ ${status} -eq 1 && ${err} == *'mo\x1bdes'* && ${err} != *${esc}* ]] && echo 1)" \
   "status ${status}: ${err}"

# ---- an output name too long once the suffixes are added: refused at the start ---------------------
long=$(printf 'n%.0s' $(seq 1 230))
run name 60 "${deck}" "${cheap[@]}" "&job output = '${long}' /"
check 'an output name of 230 characters (fits, but not with .work_precision_failed.dat.<pid>.part): exit 1 before the run' \
   "$([[ ${status} -eq 1 && ${err} == *'file name too long'* && ${out} != *label* && $(wc -l <"${work}/name.err") -eq 1 ]] && echo 1)" \
   "status ${status}: ${err}"
check 'nothing left by the refused run' \
   "$([[ -z $(find "${work}" -name "${long:0:200}*") ]] && echo 1)"

printf 'test_warnings.sh: %d checks, %d failed\n' "${n_checks}" "${n_failed}"
[[ ${n_failed} -eq 0 ]]
