#!/usr/bin/env bash
# scripts/test.sh - build and run the whole gapbeam test suite with extra run-time checks.
#
# Usage:
#   scripts/test.sh                 (from anywhere; CI calls it through .ci/run)
#
# Steps: source scripts/setup.sh (installs what is missing); build the library, the `gapbeam`
# executable and every test program once in fpm's debug profile with the flags below
# (`fpm build --tests --flag "$FLAGS"`); list the test programs (`fpm test --runner echo` with the
# same flags, which prints each test executable's path and builds nothing more); run each one on
# its own, from the repository root, so that a failing program does not hide the others; then run
# scripts/test_cli.sh, scripts/test_sweep_kill.sh, scripts/test_faults.sh (faults, full disks,
# concurrent runs, corrupted checkpoints: issue 12), scripts/test_fuzz.sh (480 mutated decks,
# under 60 s), scripts/test_labels_cli.sh (failed sweep points: exit status 5, issue 11) and
# scripts/test_users.sh (--help, --version, options, progress lines, figures in every format,
# and scripts/test_docs.py: every deck variable documented, the README's length)
# on the debug-built `gapbeam` (found with `fpm run --runner echo gapbeam`), scripts/test_slurm.sh
# (the Slurm campaign of docs/running.md against a real single-node Slurm that it installs and
# starts, about 2.5 minutes; skipped with a NOTE where Slurm cannot be had, a failure under
# CI=true), scripts/test_paraview.sh (the XDMF files in ParaView's two readers and a headless
# scene; it installs python3-paraview and xvfb with apt-get where it can, else prints a NOTE and
# skips), scripts/test_warnings.sh (warnings on standard error and in /run/warnings, checks made
# before a run), scripts/test_release.sh (the release build's random numbers equal the debug
# build's: the suite's programs run -O0 only), and
# python/tests/test_reader.py (the Python reader in python/ against h5py on every analysis's
# output of that `gapbeam`, every units attribute, the XDMF file, and every dataset documented in
# docs/outputs.md; PYTHONPATH=python, nothing is pip-installed). Everything goes to the terminal.
# GAPBEAM_GIT_COMMIT is exported from `git describe` (the result files record it).
#
# Counting: every line starting with `PASS  ` or `FAIL  ` (two spaces) is one check. A program that
# exits non-zero without printing a FAIL line (a crash, a runtime check, a time-out) adds
# `FAIL  <program> exited with status N`. The last line is `N passed, N failed`; the exit status is
# 1 if anything failed (or the build failed), else 0.
#
# Environment:
#   GAPBEAM_TEST_FLAGS    compiler flags (default below); the same string must be given to every
#                         fpm command, or fpm builds into another folder
#   GAPBEAM_TEST_TIMEOUT  seconds allowed per test program, and for test_cli.sh,
#                         test_sweep_kill.sh, test_faults.sh, test_fuzz.sh, test_users.sh,
#                         test_paraview.sh and test_reader.py
#                         (default 900)
#   GAPBEAM_FUZZ_JOBS     parallel runs of the fuzz test (default 2)
#   OMP_NUM_THREADS       passed through untouched; OPENBLAS_NUM_THREADS is set to 1
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "${root}"

# shellcheck source=setup.sh
source "${root}/scripts/setup.sh"

export OPENBLAS_NUM_THREADS=1
GAPBEAM_GIT_COMMIT=$(git -C "${root}" describe --always --dirty 2>/dev/null || echo unknown)
export GAPBEAM_GIT_COMMIT
flags=${GAPBEAM_TEST_FLAGS:-"-g -O0 -fcheck=all -fbacktrace -Wall -Wno-unused-dummy-argument"}
limit=${GAPBEAM_TEST_TIMEOUT:-900}

n_pass=0
n_fail=0
failures=()
work=$(mktemp -d "${TMPDIR:-/tmp}/gapbeam-test-XXXXXX")
trap 'rm -rf "${work}"' EXIT

# Add the PASS/FAIL lines of log file $2 (output of program $1, exit status $3) to the counts.
count() {
   local name=$1 log=$2 status=$3 p f line
   p=$(grep -c '^PASS  ' "${log}" || true)
   f=$(grep -c '^FAIL  ' "${log}" || true)
   while IFS= read -r line; do
      failures+=("${name}: ${line}")
   done < <(grep '^FAIL  ' "${log}" || true)
   if [[ ${status} -ne 0 && ${f} -eq 0 ]]; then
      if [[ ${status} -eq 124 ]]; then
         line="FAIL  ${name} exited with status ${status} (killed after ${limit} s)"
      else
         line="FAIL  ${name} exited with status ${status}"
      fi
      printf '%s\n' "${line}"
      failures+=("${name}: ${line}")
      f=1
   fi
   n_pass=$((n_pass + p))
   n_fail=$((n_fail + f))
}

# Print the paths fpm echoes for `fpm <args> --runner echo` that are executable files.
fpm_paths() {
   local line
   fpm "$@" --flag "${flags}" --runner echo 2>/dev/null | while IFS= read -r line; do
      [[ ${line} == /* ]] || line=${root}/${line}
      if [[ -f ${line} && -x ${line} ]]; then printf '%s\n' "${line}"; fi
   done
}

summary() {
   local line
   if [[ ${#failures[@]} -gt 0 ]]; then
      printf '\nFailed checks:\n'
      for line in "${failures[@]}"; do printf '  - %s\n' "${line}"; done
   fi
   printf '%d passed, %d failed\n' "${n_pass}" "${n_fail}"
   if [[ ${n_fail} -gt 0 ]]; then exit 1; fi
   exit 0
}

runner=()
if command -v timeout >/dev/null 2>&1; then
   runner=(timeout --foreground --kill-after=30 "${limit}")
fi

printf '== fpm build --tests --flag "%s"\n' "${flags}"
status=0
fpm build --tests --flag "${flags}" || status=$?
if [[ ${status} -ne 0 ]]; then
   printf 'FAIL  build: fpm build --tests exited with status %d\n' "${status}"
   failures+=("build: fpm build --tests exited with status ${status}")
   n_fail=$((n_fail + 1))
   summary
fi

mapfile -t tests < <(fpm_paths test)
if [[ ${#tests[@]} -eq 0 ]]; then
   printf 'FAIL  no test programs found (fpm test --runner echo listed none)\n'
   failures+=("fpm test --runner echo listed no test programs")
   n_fail=$((n_fail + 1))
fi

for exe in "${tests[@]}"; do
   name=$(basename "${exe}")
   printf '\n== %s\n' "${name}"
   log=${work}/${name}.log
   status=0
   "${runner[@]}" "${exe}" </dev/null 2>&1 | tee "${log}" || status=$?
   count "${name}" "${log}" "${status}"
done

printf '\n== scripts/test_cli.sh\n'
gapbeam_exe=$(fpm_paths run gapbeam | tail -n 1)
log=${work}/test_cli.log
status=0
if [[ -z ${gapbeam_exe} ]]; then
   printf 'FAIL  cli: cannot find the debug-built gapbeam executable (fpm run --runner echo)\n' \
      | tee "${log}"
else
   "${runner[@]}" bash "${root}/scripts/test_cli.sh" "${gapbeam_exe}" </dev/null 2>&1 \
      | tee "${log}" || status=$?
fi
count test_cli.sh "${log}" "${status}"

printf '\n== scripts/test_sweep_kill.sh\n'
log=${work}/test_sweep_kill.log
status=0
if [[ -n ${gapbeam_exe} ]]; then
   "${runner[@]}" bash "${root}/scripts/test_sweep_kill.sh" "${gapbeam_exe}" </dev/null 2>&1 \
      | tee "${log}" || status=$?
fi
count test_sweep_kill.sh "${log}" "${status}"

for script in test_faults.sh test_fuzz.sh test_labels_cli.sh test_users.sh test_paraview.sh \
              test_warnings.sh test_release.sh; do
   printf '\n== scripts/%s\n' "${script}"
   log=${work}/${script%.sh}.log
   status=0
   if [[ -z ${gapbeam_exe} ]]; then
      printf 'FAIL  %s: cannot find the debug-built gapbeam executable\n' "${script}" | tee "${log}"
   else
      "${runner[@]}" bash "${root}/scripts/${script}" "${gapbeam_exe}" </dev/null 2>&1 \
         | tee "${log}" || status=$?
   fi
   count "${script}" "${log}" "${status}"
done

printf '\n== scripts/test_slurm.sh\n'
log=${work}/test_slurm.log
status=0
GAPBEAM_SLURM_REQUIRED=${GAPBEAM_SLURM_REQUIRED:-${CI:-0}} GAPBEAM_SLURM_INSTALL_TIMEOUT=600 \
   "${runner[@]}" bash "${root}/scripts/test_slurm.sh" </dev/null 2>&1 | tee "${log}" || status=$?
count test_slurm.sh "${log}" "${status}"

printf '\n== python/tests/test_reader.py\n'
log=${work}/test_reader.log
status=0
if [[ -z ${gapbeam_exe} ]]; then
   printf 'FAIL  python: cannot find the debug-built gapbeam executable (fpm run --runner echo)\n' \
      | tee "${log}"
else
   PYTHONPATH="${root}/python${PYTHONPATH:+:${PYTHONPATH}}" PYTHONDONTWRITEBYTECODE=1 \
      "${runner[@]}" python3 "${root}/python/tests/test_reader.py" "${gapbeam_exe}" </dev/null 2>&1 \
      | tee "${log}" || status=$?
fi
count test_reader.py "${log}" "${status}"

summary
