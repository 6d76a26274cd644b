#!/usr/bin/env bash
# scripts/test_release.sh - the optimised build gives the debug build's numbers where they must
# not depend on the compiler's optimisation: the random numbers. The suite's programs run the
# debug build (-O0), where wrapping integer arithmetic happens to wrap; at -O3 gfortran once
# folded the SplitMix64 mixer into one constant, so that every turbulence draw, every seed and
# every random start was the same in the release build while every test passed. Checks, on
# test/decks/tube_turbulence.nml (a linear tube under turbulence, 0.7 s of CPU; the tip history):
#   - release: seeds 7 and 8 give different histories; draws 1..3 give different records
#     (their tip RMS differs in the 1e-6 digits a flat spectrum leaves to the phases);
#   - release equals debug for the same seed (history within 1e-9 of its largest value).
# Usage: scripts/test_release.sh GAPBEAM_DEBUG_EXE   (scripts/test.sh calls it; it builds the
# release profile with fpm when needed, as scripts/run.sh does).
# Prints `PASS  release: <case>` or `FAIL  release: <case> (<why>)` per check, then
# `test_release.sh: N checks, M failed`; exit status 1 if any check failed.
set -uo pipefail

if [[ $# -ne 1 ]]; then
   printf 'usage: %s GAPBEAM_DEBUG_EXE\n' "$0" >&2
   exit 2
fi
debug=$1
[[ ${debug} == /* ]] || debug=${PWD}/${debug}
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
deck=${root}/test/decks/tube_turbulence.nml
work=$(mktemp -d "${TMPDIR:-/tmp}/gapbeam-release-XXXXXX")
trap 'rm -rf "${work}"' EXIT
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
n_checks=0
n_failed=0

check() {   # check NAME OK [WHY]
   n_checks=$((n_checks + 1))
   if [[ $2 == 1 ]]; then
      printf 'PASS  release: %s\n' "$1"
   else
      n_failed=$((n_failed + 1))
      printf 'FAIL  release: %s (%s)\n' "$1" "${3:-}"
   fi
}

finish() {
   printf 'test_release.sh: %d checks, %d failed\n' "${n_checks}" "${n_failed}"
   [[ ${n_failed} -eq 0 ]]
   exit $?
}

if ! (cd "${root}" && fpm build --profile release >"${work}/build.log" 2>&1); then
   check 'fpm build --profile release' 0 "$(tail -n 3 "${work}/build.log" | tr '\n' ' ')"
   finish
fi
release=$(cd "${root}" && fpm run --profile release --runner echo gapbeam 2>/dev/null | tail -n 1)
[[ ${release} == /* ]] || release=${root}/${release}

run() {   # run EXE NAME SEED DRAWS
   (cd "${work}" && "$1" "${deck}" "&job output = '$2' /" "&turbulence seed = $3, draws = $4 /" \
      >"$2.stdout" 2>"$2.stderr")
}
ok=1
run "${release}" rel7 7 3 || ok=0
run "${release}" rel8 8 1 || ok=0
run "${debug}" dbg7 7 3 || ok=0
check 'the turbulence deck runs in both builds' "${ok}" "see ${work}/*.stderr"
[[ ${ok} == 1 ]] || finish

out=$(cd "${work}" && python3 - <<'EOF'
import h5py, numpy as np
def hist(name):
    with h5py.File(name + '.h5', 'r') as f:
        return np.array(f['/history/tip_displacement'][()], dtype=float)
def draws_rms(name):
    with h5py.File(name + '.h5', 'r') as f:
        return f['/statistics/tip_rms_displacement_ci'][()]
r7, r8, d7 = hist('rel7'), hist('rel8'), hist('dbg7')
scale = max(np.max(np.abs(d7)), 1e-300)
print('seeds', int(not np.array_equal(r7, r8)), np.max(np.abs(r7 - r8)) / scale)
print('debug', int(r7.shape == d7.shape and np.max(np.abs(r7 - d7)) <= 1e-9 * scale),
      np.max(np.abs(r7 - d7)) / scale if r7.shape == d7.shape else 'shapes differ')
ci_r, ci_d = float(np.max(draws_rms('rel7'))), float(np.max(draws_rms('dbg7')))
print('draws', int(ci_r > 0.0 and abs(ci_r - ci_d) <= 1e-6 * max(ci_d, 1e-300)), ci_r, ci_d)
EOF
)
if [[ -z ${out} ]]; then
   check 'the files read with h5py' 0 'python3/h5py failed'
   finish
fi
while read -r key good a b; do
   case ${key} in
      seeds) check 'seeds 7 and 8 give different records' "${good}" \
                "largest difference ${a} of the history's scale" ;;
      debug) check 'release equals debug for the same seed (history within 1e-9)' "${good}" \
                "largest difference ${a}" ;;
      draws) check '3 draws differ, their interval equal to the debug build'"'"'s' \
                "${good}" "tip RMS half-width ${a} (release) against ${b} (debug)" ;;
   esac
done <<<"${out}"
finish
