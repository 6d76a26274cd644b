#!/usr/bin/env bash
# scripts/test_sweep_kill.sh - a sweep killed with SIGKILL in the middle and started again with
# the same command finishes the remaining points only, and its results equal an uninterrupted
# run's (the text tables hold no timings, so they must be identical byte for byte).
#
# Usage: scripts/test_sweep_kill.sh GAPBEAM_EXE   (scripts/test.sh calls it; run from the root)
set -euo pipefail
exe=$1
dir=$(mktemp -d)
trap 'rm -rf "${dir}"' EXIT
deck=test/decks/sweep_small.nml
grid='&sweep frequency_hz = 9.4, 9.5, 9.6, 9.7, 9.8, 9.9, 10.0, 10.1, chunk = 1 /'
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
n=0; failed=0
check() {   # check NAME CONDITION-EXIT-STATUS
   n=$((n + 1))
   if [[ $2 -eq 0 ]]; then
      printf 'PASS  sweep kill: %s\n' "$1"
   else
      failed=$((failed + 1))
      printf 'FAIL  sweep kill: %s\n' "$1"
   fi
}

"${exe}" "${deck}" "${grid}" "&job output = '${dir}/ref' /" >"${dir}/ref.log" 2>&1
check 'uninterrupted sweep runs' $?

run=("${exe}" "${deck}" "${grid}" "&job output = '${dir}/cut' /")
"${run[@]}" >"${dir}/cut1.log" 2>&1 &
pid=$!
# wait until a few points are in the checkpoint, then kill without warning
header=$(( 20 + 8 + $(wc -c <"${deck}") + 200 ))
for _ in $(seq 1 600); do
   size=$(stat -c %s "${dir}/cut.checkpoint" 2>/dev/null || echo 0)
   if (( size > header + 3000 )); then break; fi
   sleep 0.02
done
kill -9 "${pid}" 2>/dev/null || true
wait "${pid}" 2>/dev/null || true
[[ -f ${dir}/cut.checkpoint && ! -f ${dir}/cut.h5 ]]
check 'killed sweep leaves its checkpoint and no result file' $?

"${run[@]}" >"${dir}/cut2.log" 2>&1
check 'the same command finishes the sweep' $?
already=$(sed -n 's/.* \([0-9][0-9]*\) already in the checkpoint.*/\1/p' "${dir}/cut2.log")
printf 'NOTE  sweep kill: the restart found %s of 16 points in the checkpoint\n' "${already:-?}"
(( ${already:-0} > 0 && ${already:-0} < 16 ))
check 'the restart ran only the missing points' $?
[[ ! -f ${dir}/cut.checkpoint ]]
check 'the finished sweep removed its checkpoint' $?
cmp -s "${dir}/ref.sweep.dat" "${dir}/cut.sweep.dat" \
   && cmp -s "${dir}/ref.bifurcation.dat" "${dir}/cut.bifurcation.dat"
check 'killed and resumed results equal the uninterrupted run' $?

printf 'test_sweep_kill.sh: %d checks, %d failed\n' "${n}" "${failed}"
(( failed == 0 ))
