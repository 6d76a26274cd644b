#!/usr/bin/env bash
# scripts/bench_sweep.sh - OpenMP scaling of the forcing sweep, measured side by side.
#
# Usage:
#   scripts/bench_sweep.sh [DECK] [THREADS ...]
#   default: inputs/sweep_grid_gap.nml on a 64 x 32 frequency x amplitude grid, 300 transient
#   and 200 recorded periods per point, with 1 and 2 threads (give e.g. 1 2 4 8 16 on a bigger
#   machine).
#
# Builds the release profile, then runs the sweep once per thread count (no checkpoint, no
# progress), recording the wall time, points per second, the parallel efficiency
# (t_1 / (p t_p)), and the peak resident memory (VmHWM polled from /proc). It checks that every
# thread count gave the same results (the .sweep.dat and .bifurcation.dat tables byte for byte).
# Output: a table on stdout and in bench_results/bench_sweep.txt.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "${root}"
deck=${1:-inputs/sweep_grid_gap.nml}
shift || true
threads=("$@")
[[ ${#threads[@]} -gt 0 ]] || threads=(1 2)

# shellcheck source=setup.sh
source "${root}/scripts/setup.sh"
export OPENBLAS_NUM_THREADS=1
build_log=$(mktemp "${TMPDIR:-/tmp}/gapbeam-build-XXXXXX")
if ! fpm build --profile release >"${build_log}" 2>&1; then
   cat "${build_log}" >&2; exit 1
fi
exe=""
while IFS= read -r line; do
   [[ ${line} == /* ]] || line=${root}/${line}
   if [[ -f ${line} && -x ${line} ]]; then exe=${line}; fi
done < <(fpm run --profile release --runner echo gapbeam 2>>"${build_log}")
rm -f "${build_log}"
[[ -n ${exe} ]] || { printf 'bench_sweep: cannot find the gapbeam executable\n' >&2; exit 1; }

out=bench_results
mkdir -p "${out}"
grid=${GAPBEAM_BENCH_GRID:-'&sweep n_frequency = 64, n_amplitude = 32, progress = .false., checkpoint = .false. /'}
horizon='&solver transient_periods = 300, record_periods = 200 /'
report=${out}/bench_sweep.txt
{
   printf 'sweep benchmark: %s, %s\n' "${deck}" "${grid}"
   printf 'machine: %s cores, %s\n' "$(nproc)" "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
   printf '%8s %10s %8s %12s %11s %14s\n' threads 'wall [s]' points 'points/s' efficiency \
      'peak RSS [MB]'
} | tee "${report}"
t1=""
for p in "${threads[@]}"; do
   prefix=${out}/sweep_t${p}
   start=$(date +%s.%N)
   OMP_NUM_THREADS=${p} "${exe}" "${deck}" "${grid}" "${horizon}" \
      "&job output = '${prefix}' /" >"${prefix}.log" 2>&1 &
   pid=$!
   peak=0
   while kill -0 "${pid}" 2>/dev/null; do
      kb=$(awk '/VmHWM/ {print $2}' "/proc/${pid}/status" 2>/dev/null || echo 0)
      (( ${kb:-0} > peak )) && peak=${kb}
      sleep 0.2
   done
   wait "${pid}"
   end=$(date +%s.%N)
   wall=$(awk -v a="${start}" -v b="${end}" 'BEGIN {print b - a}')
   points=$(sed -n 's/^sweep: \([0-9]*\) points in .*/\1/p' "${prefix}.log")
   [[ -n ${t1} ]] || t1=${wall}
   awk -v p="${p}" -v w="${wall}" -v n="${points}" -v t1="${t1}" -v kb="${peak}" \
      'BEGIN {printf "%8d %10.2f %8d %12.2f %10.1f%% %14.1f\n", p, w, n, n / w, \
              100 * t1 / (p * w), kb / 1024}' | tee -a "${report}"
   if [[ ${p} != "${threads[0]}" ]]; then
      if cmp -s "${out}/sweep_t${threads[0]}.sweep.dat" "${prefix}.sweep.dat" && \
         cmp -s "${out}/sweep_t${threads[0]}.bifurcation.dat" "${prefix}.bifurcation.dat"; then
         printf '         results identical to %s thread(s)\n' "${threads[0]}" | tee -a "${report}"
      else
         printf '         RESULTS DIFFER from %s thread(s)\n' "${threads[0]}" | tee -a "${report}"
      fi
   fi
done
grep '^labels:' "${out}/sweep_t${threads[0]}.log" | tee -a "${report}"
