#!/usr/bin/env bash
# scripts/test_labels_cli.sh - failed sweep points through the real gapbeam executable (issue 11):
# a sweep in which a point fails writes all its files and exits with status 5 (not 0, not 1),
# naming the point on standard error; so do a shard holding the point and the merge of the
# shards (which says so on standard error); a shard without the point exits 0.
#
# Usage:
#   scripts/test_labels_cli.sh GAPBEAM_EXE
#   (scripts/test.sh calls it with the debug-built executable)
#
# The deck is test/decks/sdof_impact.nml (a single-dof impact oscillator, exact integrator)
# made cheap, with the amplitudes 1 mm and 1e300 m: the exact integrator refuses the second.
# Prints `PASS  labels-cli: <case>` or `FAIL  labels-cli: <case> (<why>)` per check, then
# `test_labels_cli.sh: N checks, M failed`; exit status 1 if any check failed.
set -euo pipefail

if [[ $# -ne 1 ]]; then
   printf 'usage: %s GAPBEAM_EXE\n' "$0" >&2
   exit 2
fi
exe=$1
[[ ${exe} == /* ]] || exe=${PWD}/${exe}
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
deck=${root}/test/decks/sdof_impact.nml
work=$(mktemp -d "${TMPDIR:-/tmp}/gapbeam-labels-cli-XXXXXX")
trap 'rm -rf "${work}"' EXIT
n_checks=0
n_failed=0

check() {   # check NAME OK [WHY]
   n_checks=$((n_checks + 1))
   if [[ $2 == 1 ]]; then
      printf 'PASS  labels-cli: %s\n' "$1"
   else
      n_failed=$((n_failed + 1))
      printf 'FAIL  labels-cli: %s (%s)\n' "$1" "${3:-}"
   fi
}

cheap=("&job analysis = 'sweep' /"
       "&sweep amplitude_pp = 1.0e-3, 1.0e300, progress = .false., checkpoint = .false. /"
       "&solver transient_periods = 20, record_periods = 40 /"
       "&diagnostics lyapunov_periods = 20, lyapunov_max_periods = 20, certify = .false. /")

# run NAME ARGS...: run in the work directory; sets status, out and err
run() {
   local name=$1
   shift
   status=0
   (cd "${work}" && "${exe}" "$@" >"${name}.out" 2>"${name}.err") || status=$?
   out=$(<"${work}/${name}.out")
   err=$(<"${work}/${name}.err")
}

run whole "${deck}" "${cheap[@]}" "&job output = 'whole' /"
check 'sweep with a failing point exits with status 5' "$([[ ${status} -eq 5 ]] && echo 1)" \
   "status ${status}"
check 'the failing point is listed on standard error' \
   "$([[ ${err} == *'sweep: failed: point 2 '* && ${err} == *'gapbeam_exact'* ]] && echo 1)" \
   "stderr: ${err}"
check 'its files are written, no temporary left' \
   "$([[ -f ${work}/whole.h5 && -z $(find "${work}" -name '*.part') ]] && echo 1)"
check 'standard output counts the failed run' \
   "$([[ ${out} == *'failed runs: 1'* ]] && echo 1)" "stdout: ${out}"

run shard1 "${deck}" "${cheap[@]}" "&job output = 'part' /" --shard 1/2
check 'the shard without the failing point exits 0' "$([[ ${status} -eq 0 ]] && echo 1)" \
   "status ${status}: ${err}"
run shard2 "${deck}" "${cheap[@]}" "&job output = 'part' /" --shard 2/2
check 'the shard with the failing point exits 5' "$([[ ${status} -eq 5 ]] && echo 1)" \
   "status ${status}"
run merge merge merged.h5 part.shard_1_of_2.h5 part.shard_2_of_2.h5
check 'the merge of the shards exits 5 and writes the merged file' \
   "$([[ ${status} -eq 5 && -f ${work}/merged.h5 ]] && echo 1)" "status ${status}: ${out} ${err}"
check 'the merge says so on standard error (was: nothing there)' \
   "$([[ ${err} == *'gapbeam merge: 1 failed run(s) in the shards'* ]] && echo 1)" "stderr: ${err}"

run good "${deck}" "${cheap[@]}" "&job output = 'good' /" "&sweep amplitude_pp = 1.0e-3 /"
check 'a sweep without a failure exits 0' "$([[ ${status} -eq 0 ]] && echo 1)" \
   "status ${status}: ${err}"

printf 'test_labels_cli.sh: %d checks, %d failed\n' "${n_checks}" "${n_failed}"
[[ ${n_failed} -eq 0 ]]
