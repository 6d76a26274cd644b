#!/usr/bin/env bash
# scripts/test_users.sh - what a user meets first, through the real executable and scripts:
# --help and --version, command-line options, progress lines, the commit recorded in the files,
# figures in every format, the documentation (scripts/test_docs.py).
#
# Usage: scripts/test_users.sh GAPBEAM_EXE   (scripts/test.sh calls it; run from the root)
#
# Checks (one PASS/FAIL line each):
#   --help / -h exit 0 and print the usage, every analysis and the exit statuses; --version /
#   -V exit 0 and print the version of fpm.toml and the commit of GAPBEAM_GIT_COMMIT; an unknown
#   option exits 2 with an error line and the usage; --progress without a number is an error;
#   a transient that runs longer than the progress interval (RK45 on a stiff stop) prints
#   progress lines on a non-terminal stderr with percent, periods done, rate, time left as
#   h:mm:ss, time and step, and a last line at 100 %; --quiet prints none; a continuation sweep
#   line reports points done before its end; the HDF5 file records GAPBEAM_GIT_COMMIT;
#   scripts/plot.sh writes PNG, PDF and SVG (a %PDF / <svg header) and refuses another format;
#   fpm.toml declares gapbeam as its only executable (the benchmark is an example);
#   scripts/test_docs.py (every deck variable documented, README within its length).
#   scripts/code_metrics.py --check (the folder rule of src/, no file over 1,000 lines, no
#   procedure over 150 lines).
# Prints `test_users.sh: N checks, M failed`; exit status 1 if a check failed.
set -uo pipefail
exe=$1
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
dir=$(mktemp -d "${TMPDIR:-/tmp}/gapbeam-users-XXXXXX")
trap 'rm -rf "${dir}"' EXIT
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
n=0
failed=0
check() {   # check NAME STATUS [WHY]
   n=$((n + 1))
   if [[ $2 -eq 0 ]]; then
      printf 'PASS  users: %s\n' "$1"
   else
      failed=$((failed + 1))
      printf 'FAIL  users: %s%s\n' "$1" "${3:+ ($3)}"
   fi
}

version=$(sed -n 's/^version *= *"\([^"]*\)".*/\1/p' "${root}/fpm.toml" | head -n 1)

for opt in --help -h; do
   out=$("${exe}" "${opt}" 2>&1); st=$?
   ok=0
   [[ ${st} -eq 0 ]] || ok=1
   for w in 'usage: gapbeam DECK' modes calibrate transient sweep work_precision stability \
            model_size continuation 'Exit status' '0 done' '1 error' '2 usage' '3 a sweep' \
            '4 the output' '5 a sweep' '--quiet' '--progress' '--shard' '--time-limit' 'merge' \
            '--version' 'GAPBEAM_BACKTRACE' 'docs/'; do
      [[ ${out} == *"${w}"* ]] || { ok=1; why="no '${w}'"; }
   done
   check "gapbeam ${opt}: exit 0, usage, the analyses, every exit status (0-5), every option, docs" "${ok}" \
      "status ${st}; ${why:-}"
done

for opt in --version -V; do
   out=$(GAPBEAM_GIT_COMMIT=abc1234-test "${exe}" "${opt}" 2>&1); st=$?
   [[ ${st} -eq 0 && ${out} == "gapbeam ${version}"* && ${out} == *"commit: abc1234-test"* ]]
   check "gapbeam ${opt}: exit 0, version ${version} as in fpm.toml, the commit" $? "${out}"
done
out=$(env -u GAPBEAM_GIT_COMMIT "${exe}" --version 2>&1)
[[ ${out} == *"commit: unknown"* ]]
check "gapbeam --version without GAPBEAM_GIT_COMMIT says commit unknown" $? "${out}"

"${exe}" --frobnicate >"${dir}/o" 2>"${dir}/e"; st=$?
[[ ${st} -eq 2 ]] && grep -q "^error: unknown option '--frobnicate'" "${dir}/e" \
   && grep -q '^usage: gapbeam' "${dir}/e"
check "an unknown option: exit 2, an error line naming it and the usage" $? \
   "status ${st}: $(head -c 300 "${dir}/e")"
"${exe}" "${root}/inputs/moon_shaw_modes.nml" --progress >"${dir}/o" 2>"${dir}/e"; st=$?
[[ ${st} -ne 0 ]] && grep -q -- '--progress needs a number' "${dir}/e"
check "--progress without a number is an error" $? "status ${st}"
"${exe}" "${root}/inputs/moon_shaw_modes.nml" --progress=-3 >"${dir}/o" 2>"${dir}/e"; st=$?
[[ ${st} -ne 0 ]] && grep -q -- "--progress '-3'" "${dir}/e"
check "--progress -3 is an error naming the value" $? "status ${st}"

# A slow transient: RK45 on a stiff stop (the issue's 44 s per period, shortened).
slow=("${root}/test/decks/moon_shaw_10p5hz_half_element.nml"   # RK45 needs a mass at every dof
   "&solver method = 'rk45', step_control = 'embedded', transient_periods = 3, record_periods = 3 /"
   "&stops rule_factor = 0, stiffness = 1.0e7 /"
   "&diagnostics lyapunov_periods = 2, lyapunov_max_periods = 2, settle_windows = 0, certify = .false. /")
# (no settling extension, no adaptive exponent, no certificate: the run is the 10 periods the
# meter expects; with them the meter's total grows to the periods actually run)
GAPBEAM_GIT_COMMIT=feedbee-test "${exe}" "${slow[@]}" "&job output = '${dir}/slow' /" \
   --progress 0.2 >"${dir}/slow.out" 2>"${dir}/slow.err"; st=$?
re='^transient: [0-9]+\.[0-9] % \([0-9.]+/10 periods\), [0-9.]+ periods/s, [0-9]+:[0-9][0-9]:[0-9][0-9] left; t = [0-9.]+ s, dt = [0-9.]+E[-+][0-9]+ s$'
lines=$(grep -c -E "${re}" "${dir}/slow.err")
[[ ${st} -eq 0 && ${lines} -ge 1 ]]
check "a slow transient prints progress lines (percent, periods, rate, h:mm:ss left, t, dt)" $? \
   "status ${st}, ${lines} lines: $(head -c 400 "${dir}/slow.err")"
grep -q -E '^transient: 100\.0 % \(10/10 periods\) in [0-9]+:[0-9][0-9]:[0-9][0-9]' "${dir}/slow.err"
check "its last progress line is at 100 % with the time taken" $? "$(tail -n 2 "${dir}/slow.err")"
[[ $(grep -c $'\r' "${dir}/slow.err") -eq 0 ]]
check "progress on a non-terminal stderr: whole lines, no carriage returns" $?
"${exe}" "${slow[@]}" "&job output = '${dir}/quiet' /" --progress 0.2 --quiet >"${dir}/q.out" \
   2>"${dir}/q.err"; st=$?
[[ ${st} -eq 0 && ! -s ${dir}/q.err ]]
check "--quiet: no progress lines, nothing on stderr" $? "status ${st}: $(head -c 200 "${dir}/q.err")"
if command -v python3 >/dev/null 2>&1 && python3 -c 'import h5py' 2>/dev/null; then
   commit=$(python3 -c "import h5py,sys; print(h5py.File(sys.argv[1], 'r').attrs['git_commit'])" \
      "${dir}/slow.h5" 2>&1)
   [[ ${commit} == feedbee-test ]]
   check "the HDF5 file records GAPBEAM_GIT_COMMIT (root attribute git_commit)" $? "${commit}"
else
   printf 'NOTE  users: python3 with h5py missing: the git_commit attribute is not checked\n'
fi

# A continuation line reports its progress in rounds of points, before its end.
"${exe}" "${root}/inputs/sweep_line_4mm.nml" \
   "&sweep n_frequency = 20, frequency_end_hz = 9.45, checkpoint = .false. /" \
   "&solver transient_periods = 20, record_periods = 10 /" "&diagnostics lyapunov_periods = 4 /" \
   "&job output = '${dir}/line' /" --progress 0.001 >"${dir}/line.out" 2>"${dir}/line.err"; st=$?
[[ ${st} -eq 0 ]] && grep -q -E '^sweep: [0-9.]+ % \((8|16)/20 points\), [0-9.]+ points/s, [0-9]+:[0-9][0-9]:[0-9][0-9] left$' "${dir}/line.err"
check "a continuation line reports points done before its end (rounds of points)" $? \
   "status ${st}: $(head -c 300 "${dir}/line.err")"

# Figures in every format.
if command -v gnuplot >/dev/null 2>&1; then
   "${exe}" "${root}/inputs/moon_shaw_10p5hz.nml" "&solver transient_periods = 3, record_periods = 6 /" \
      "&diagnostics lyapunov_periods = 2 /" "&output state_history = .true., history_periods = 1 /" \
      "&job output = '${dir}/fig' /" -q >/dev/null 2>&1
   for f in png pdf svg; do
      bash "${root}/scripts/plot.sh" --format "${f}" transient "${dir}/fig" >/dev/null 2>"${dir}/plot.err"
      st=$?
      head=$(head -c 5 "${dir}/fig.poincare.${f}" 2>/dev/null | tr -d '\0')
      case ${f} in
         png) want=$'\x89PNG' ;;
         pdf) want='%PDF-' ;;
         svg) want='<?xml' ;;
      esac
      [[ ${st} -eq 0 && -s ${dir}/fig.history.${f} && ${head} == "${want}"* ]]
      check "scripts/plot.sh --format ${f}: the transient's figures are ${f} files" $? \
         "status ${st}: $(head -c 200 "${dir}/plot.err")"
   done
   [[ -s ${dir}/fig.animation.gif && $(head -c 3 "${dir}/fig.animation.gif") == GIF ]]
   check "scripts/plot.sh draws the animation (GIF) of a run with a state history" $?
   bash "${root}/scripts/plot.sh" --format bmp transient "${dir}/fig" >/dev/null 2>&1; st=$?
   [[ ${st} -eq 2 ]]
   check "scripts/plot.sh --format bmp: usage error (exit 2)" $? "status ${st}"
else
   printf 'NOTE  users: gnuplot missing: figures not checked\n'
fi

# One executable: the benchmark is an fpm example.
execs=$(grep -c '^\[\[executable\]\]' "${root}/fpm.toml")
[[ ${execs} -eq 1 ]] && grep -A1 '^\[\[executable\]\]' "${root}/fpm.toml" | grep -q 'name = "gapbeam"' \
   && grep -q '^\[\[example\]\]' "${root}/fpm.toml"
check "fpm.toml: gapbeam is the only executable, the benchmark an example" $? "${execs} executables"

# The documentation.
if command -v python3 >/dev/null 2>&1; then
   python3 "${root}/scripts/test_docs.py" "${root}"
   check "scripts/test_docs.py ran to the end" $?
   why=$(python3 "${root}/scripts/code_metrics.py" --check --root "${root}")
   check "house rules: the folder rule, files <= 1000 lines, procedures <= 150 lines" $? \
      "$(printf '%s' "${why}" | head -n 3 | tr '\n' ';')"
fi

printf 'test_users.sh: %d checks, %d failed\n' "${n}" "${failed}"
[[ ${failed} -eq 0 ]]
