#!/usr/bin/env bash
# scripts/slurm_sweep.sh - run a gapbeam sweep deck as a Slurm job array (one shard per array task)
# and merge the shards' result files.
#
# Usage (from the repository root, so that the deck's relative output prefix results/... lands
# there; Slurm does not create the log folder, hence the mkdir). The whole campaign, with its
# settings and what to do when a task fails, is in docs/running.md ("Slurm job arrays: a
# campaign on a cluster"), which scripts/test_slurm.sh runs as written against a real Slurm:
#   mkdir -p logs
#   fpm build --profile release                                          # once, before submitting
#   export GAPBEAM=$(realpath "$(fpm run --profile release --runner echo gapbeam | tail -n 1)")
#   export GAPBEAM_AUTO_REQUEUE=1
#   jid=$(sbatch --parsable --array=1-16%8 --time=02:00:00 scripts/slurm_sweep.sh inputs/sweep_grid_gap.nml)
#   sbatch --dependency=afterok:${jid%%;*} --array=1 --cpus-per-task=1 --time=00:30:00 \
#          scripts/slurm_sweep.sh --merge inputs/sweep_grid_gap.nml
#
#   scripts/slurm_sweep.sh [--shards N] [--time-limit S] [--shard-costs FILE.h5] DECK [OVERRIDE ...]
#                                                                          (an array task)
#   scripts/slurm_sweep.sh --merge [--shards N] [--prefix PREFIX] DECK [OVERRIDE ...]
#
# Sweep (an array task): creates the directory of the output prefix (below) when missing, runs
# `gapbeam DECK --shard I/N [--time-limit S] [--shard-costs FILE.h5] [OVERRIDE ...]` in the
# submission directory and exits with the program's status. The program writes
# PREFIX.shard_I_of_N.h5 (and .sweep.dat, .bifurcation.dat), PREFIX being the deck's
# `&job output`; points are dealt to the shards round robin, or with --shard-costs FILE.h5 (or
# GAPBEAM_SHARD_COSTS=FILE.h5; the same file for every task) by their costs in that earlier
# result file of the same grid (work items: a point in mode 'independent', a whole line in mode
# 'continuation', so a continuation sweep has at most as many useful shards as lines).
#   N = --shards N, else SLURM_ARRAY_TASK_COUNT, else SLURM_ARRAY_TASK_MAX - SLURM_ARRAY_TASK_MIN
#       + 1, else 1 (not in an array: the whole sweep, PREFIX.h5, nothing to merge);
#   I = SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN + 1 (1-based), or with --shards N the array
#       index itself (SLURM_ARRAY_TASK_ID), so that single shards can be run again on their own:
#       sbatch --array=5,9 scripts/slurm_sweep.sh --shards 16 DECK
# Every task must get the same DECK and OVERRIDEs: they are part of the deck text that the
# checkpoint and the merge compare (a shard run with other overrides is refused, never mixed).
#
# Time limit and resuming: the task runs `gapbeam ... --time-limit S`, S = the seconds left to the
# task (SLURM_JOB_END_TIME, else `squeue -o %L` of JOBID_I) less a margin (GAPBEAM_TIME_MARGIN, default 300 s:
# one chunk of points and the file writing must fit in it; half the time left when that is less
# than twice the margin); `--time-limit S` here or GAPBEAM_TIME_LIMIT=S sets S, 0 switches it off
# (also the default outside Slurm). The limit is not part of the deck text, so it may differ from
# task to task and from run to run. When the program reaches it, it stops after the current
# chunk with exit status 3: the finished points are kept in PREFIX.shard_I_of_N.checkpoint and
# running the same shard again (same DECK, OVERRIDEs and N) computes only the rest. To resume:
# `scontrol requeue JOBID_I` (the header asks for --requeue, which also re-runs a task after a
# node failure or preemption, resuming from the checkpoint the same way), or
# `sbatch --array=I ... --shards N DECK` as above. With GAPBEAM_AUTO_REQUEUE=1 in the environment
# a task that exits with status 3 requeues itself (`scontrol requeue`), at most
# GAPBEAM_MAX_REQUEUE times (default 10): every run that reaches the time limit has finished at
# least one chunk, so this ends. Slurm holds a requeued task for about two minutes before it
# may start again. A task stopped by status 3 and not requeued counts as failed for
# `--dependency=afterok`: submit the merge again once every shard has finished.
#
# SIGTERM (Slurm's signal at the hard time limit, on preemption and on scancel, KillWait seconds
# before SIGKILL): the program runs as a child that the script waits for; it finishes its chunk,
# keeps the checkpoint and exits with 3, and the script, which Slurm signals too, reports it and
# does not requeue the task (a cancelled task stays cancelled). Outside Slurm the script passes a
# SIGTERM (or Ctrl-C) on to the program as SIGTERM.
#
# Merge (--merge): runs `gapbeam merge PREFIX.h5 PREFIX.shard_1_of_N.h5 ... PREFIX.shard_N_of_N.h5`
# and then `scripts/plot.sh sweep PREFIX` when gnuplot is there (a plotting failure is reported,
# not fatal). PREFIX: --prefix PREFIX, else the last `output = '...'` of the `&job` group in DECK
# and then in the OVERRIDEs (comments removed), else results/<deck file name without extension>
# (the program's default). N: --shards N, else the one N of the existing PREFIX.shard_*_of_N.h5
# files (an error when files of several N are there). Missing shard files are listed (with a
# note for those that left a checkpoint) and nothing is merged. Run as an array of more than one
# task, only the first task merges; the others exit 0.
#
# Environment:
#   GAPBEAM               the gapbeam executable; default: `fpm run --profile release --runner echo
#                         gapbeam` in the repository root (as scripts/run.sh; fpm builds first if
#                         the build is out of date, so build once before submitting, or better set
#                         GAPBEAM: sixteen tasks must not build at once), else `gapbeam` on PATH
#                         or in ~/.local/bin (`fpm install --profile release`).
#   GAPBEAM_TIME_LIMIT, GAPBEAM_TIME_MARGIN, GAPBEAM_AUTO_REQUEUE, GAPBEAM_MAX_REQUEUE,
#   GAPBEAM_SHARD_COSTS: see above.
#   OMP_NUM_THREADS       set to SLURM_CPUS_PER_TASK (1 if unset): threads over sweep points.
#   OPENBLAS_NUM_THREADS  set to 1 (with threaded BLAS the results change with the thread count).
#   GAPBEAM_GIT_COMMIT    recorded in the result files; when unset, taken from `git describe` in
#                         the repository (the commit of the sources there, which should be the
#                         ones GAPBEAM was built from).
# Exit status: the program's (0 done; 1 error; 3 time limit reached, checkpoint kept; 4 the
# output prefix is locked by another run: two tasks were given the same shard; 5 the shard's
# (or the merged) file is written but some of its points failed); 2 on bad usage or when the
# executable or shard files are missing.
# Slurm opens the log file (--output=logs/...) before the script runs and does not create its
# directory: make logs/ in the submission directory before sbatch. The log is opened for
# appending (--open-mode=append), so a requeued task's log keeps its earlier runs.
#
# Defaults of the array tasks (options given to sbatch on its command line take precedence):
#SBATCH --job-name=gapbeam-sweep
#SBATCH --array=1-16
#SBATCH --ntasks=1
#SBATCH --cpus-per-task=8
#SBATCH --time=02:00:00
#SBATCH --requeue
#SBATCH --open-mode=append
#SBATCH --output=logs/%x_%A_%a.out
set -euo pipefail

script_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)

if [[ ${1:-} == -h || ${1:-} == --help ]]; then
   sed -n '2,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "${BASH_SOURCE[0]}"
   exit 0
fi

usage() {
   printf 'usage: scripts/slurm_sweep.sh [--merge] [--shards N] [--time-limit S] [--shard-costs FILE.h5] [--prefix PREFIX] DECK [OVERRIDE ...]\n' >&2
   printf '       (scripts/slurm_sweep.sh --help for the whole story)\n' >&2
   exit 2
}

die() {
   printf 'slurm_sweep: error: %s\n' "$1" >&2
   exit 2
}

# The repository root: the script's parent when run in place; under sbatch the script runs from
# Slurm's spool, so the submission directory (or the working directory) is used instead.
if [[ -f ${script_dir}/../fpm.toml ]]; then
   root=$(cd "${script_dir}/.." && pwd)
elif [[ -n ${SLURM_SUBMIT_DIR:-} && -f ${SLURM_SUBMIT_DIR}/fpm.toml ]]; then
   root=${SLURM_SUBMIT_DIR}
else
   root=${PWD}
fi

merge=0
shards=""
prefix=""
shard_costs=${GAPBEAM_SHARD_COSTS:-}
time_limit=${GAPBEAM_TIME_LIMIT:-}
while [[ $# -gt 0 ]]; do
   case $1 in
      --merge) merge=1; shift ;;
      --shards)
         [[ $# -ge 2 ]] || usage
         shards=$2; shift 2 ;;
      --shards=*) shards=${1#--shards=}; shift ;;
      --prefix)
         [[ $# -ge 2 ]] || usage
         prefix=$2; shift 2 ;;
      --prefix=*) prefix=${1#--prefix=}; shift ;;
      --time-limit)
         [[ $# -ge 2 ]] || usage
         time_limit=$2; shift 2 ;;
      --time-limit=*) time_limit=${1#--time-limit=}; shift ;;
      --shard-costs)
         [[ $# -ge 2 ]] || usage
         shard_costs=$2; shift 2 ;;
      --shard-costs=*) shard_costs=${1#--shard-costs=}; shift ;;
      --) shift; break ;;
      -*) printf 'slurm_sweep: unknown option %s\n' "$1" >&2; usage ;;
      *) break ;;
   esac
done
[[ $# -ge 1 ]] || usage
deck=$1
shift
overrides=("$@")
[[ -f ${deck} ]] || die "deck ${deck} not found (relative to $(pwd))"
if [[ -n ${shards} && ! ${shards} =~ ^[1-9][0-9]*$ ]]; then
   die "--shards ${shards}: expected a whole number >= 1"
fi
if [[ -n ${time_limit} && ! ${time_limit} =~ ^[0-9]+$ ]]; then
   die "--time-limit ${time_limit}: expected a whole number of seconds (0: none)"
fi
if [[ -n ${shard_costs} && ! -f ${shard_costs} ]]; then
   die "--shard-costs ${shard_costs}: no such file (relative to $(pwd))"
fi

# gapbeam's executable (see GAPBEAM above).
find_gapbeam() {
   local line exe=""
   if [[ -n ${GAPBEAM:-} ]]; then
      [[ -x ${GAPBEAM} ]] || die "GAPBEAM=${GAPBEAM} is not an executable file"
      printf '%s' "${GAPBEAM}"
      return
   fi
   if command -v fpm >/dev/null 2>&1 && [[ -f ${root}/fpm.toml ]]; then
      while IFS= read -r line; do
         [[ ${line} == /* ]] || line=${root}/${line}
         if [[ -f ${line} && -x ${line} ]]; then exe=${line}; fi
      done < <(cd "${root}" && fpm run --profile release --runner echo gapbeam 2>/dev/null)
   fi
   if [[ -z ${exe} ]] && command -v gapbeam >/dev/null 2>&1; then exe=$(command -v gapbeam); fi
   if [[ -z ${exe} && -x ${HOME:-/nonexistent}/.local/bin/gapbeam ]]; then
      exe=${HOME}/.local/bin/gapbeam
   fi
   [[ -n ${exe} ]] || die "no gapbeam executable: set GAPBEAM, or build with fpm build --profile release in ${root}"
   printf '%s' "${exe}"
}

# Namelist text without comments: '!' outside a quoted string starts one (quotes may be ' or ").
strip_comments() {
   awk '{
      out = ""; q = ""
      for (i = 1; i <= length($0); i++) {
         c = substr($0, i, 1)
         if (q == "") {
            if (c == "!") break
            if (c == "\047" || c == "\"") q = c
         } else if (c == q) {
            q = ""
         }
         out = out c
      }
      print out
   }'
}

# The last `output = '...'` (or "...") assignment in the namelist text on stdin, or nothing.
# (`&output` is a group name, never followed by '=', so it does not match.)
last_output() {
   strip_comments | tr '\n' ' ' \
      | grep -o -i -E "(^|[^[:alnum:]_%&])output[[:space:]]*=[[:space:]]*('[^']*'|\"[^\"]*\")" \
      | tail -n 1 | sed -E "s/^[^=]*=[[:space:]]*//; s/^['\"]//; s/['\"]\$//" || true
}

deck_prefix() {
   local p o
   p=$(last_output <"${deck}")
   for o in "${overrides[@]+"${overrides[@]}"}"; do
      local po
      po=$(printf '%s\n' "${o}" | last_output)
      if [[ -n ${po} ]]; then p=${po}; fi
   done
   if [[ -z ${p} ]]; then
      p=$(basename -- "${deck}")
      p=results/${p%.*}
   fi
   printf '%s' "${p}"
}

# Seconds in a Slurm time ([days-]hours:minutes:seconds, minutes:seconds or minutes), or nothing
# for UNLIMITED, INVALID and the like.
slurm_seconds() {
   local t=$1 d=0 h=0 m=0 x=0
   if [[ ${t} =~ ^([0-9]+)-([0-9]+):([0-9]+):([0-9]+)$ ]]; then
      d=${BASH_REMATCH[1]}; h=${BASH_REMATCH[2]}; m=${BASH_REMATCH[3]}; x=${BASH_REMATCH[4]}
   elif [[ ${t} =~ ^([0-9]+):([0-9]+):([0-9]+)$ ]]; then
      h=${BASH_REMATCH[1]}; m=${BASH_REMATCH[2]}; x=${BASH_REMATCH[3]}
   elif [[ ${t} =~ ^([0-9]+):([0-9]+)$ ]]; then
      m=${BASH_REMATCH[1]}; x=${BASH_REMATCH[2]}
   elif [[ ${t} =~ ^([0-9]+)$ ]]; then
      m=${BASH_REMATCH[1]}
   else
      return 0
   fi
   printf '%d' "$((10#${d} * 86400 + 10#${h} * 3600 + 10#${m} * 60 + 10#${x}))"
}

# The seconds to pass as --time-limit (see above), or nothing for none.
task_time_limit() {
   local left="" margin=${GAPBEAM_TIME_MARGIN:-300} now limit
   if [[ -n ${time_limit} ]]; then
      if [[ ${time_limit} -gt 0 ]]; then printf '%d' "${time_limit}"; fi
      return 0
   fi
   [[ -n ${SLURM_JOB_ID:-} ]] || return 0
   now=$(date +%s)
   if [[ ${SLURM_JOB_END_TIME:-} =~ ^[0-9]+$ ]]; then
      left=$((SLURM_JOB_END_TIME - now))
   elif command -v squeue >/dev/null 2>&1; then
      # this task's own line: `squeue -j` of the first task's job id lists the whole array
      local job=${SLURM_JOB_ID}
      if [[ -n ${SLURM_ARRAY_JOB_ID:-} && -n ${SLURM_ARRAY_TASK_ID:-} ]]; then
         job=${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID}
      fi
      left=$(slurm_seconds "$(squeue -h -j "${job}" -o %L 2>/dev/null | head -n 1)")
   fi
   [[ -n ${left} && ${left} -gt 0 ]] || return 0
   [[ ${margin} =~ ^[0-9]+$ ]] || margin=300
   if ((left > 2 * margin)); then limit=$((left - margin)); else limit=$((left / 2)); fi
   if ((limit < 1)); then limit=1; fi
   printf '%d' "${limit}"
}

export OMP_NUM_THREADS=${SLURM_CPUS_PER_TASK:-1}
export OPENBLAS_NUM_THREADS=1
export GFORTRAN_UNBUFFERED_PRECONNECTED=y
if [[ -z ${GAPBEAM_GIT_COMMIT:-} ]]; then
   GAPBEAM_GIT_COMMIT=$(git -C "${root}" describe --always --dirty 2>/dev/null || echo unknown)
fi
export GAPBEAM_GIT_COMMIT

task_id=${SLURM_ARRAY_TASK_ID:-}
task_min=${SLURM_ARRAY_TASK_MIN:-${task_id}}
task_max=${SLURM_ARRAY_TASK_MAX:-${task_id}}

if [[ ${merge} -eq 1 ]]; then
   if [[ -n ${task_id} && ${task_id} != "${task_min}" ]]; then
      printf 'slurm_sweep: merge: array task %s: only the first task (%s) merges; nothing to do\n' \
         "${task_id}" "${task_min}"
      exit 0
   fi
   [[ -n ${prefix} ]] || prefix=$(deck_prefix)
   if [[ -z ${shards} ]]; then
      mapfile -t found < <(
         shopt -s nullglob
         for f in "${prefix}".shard_*_of_*.h5; do
            f=${f##*_of_}
            printf '%s\n' "${f%.h5}"
         done | sort -u -n)
      if [[ ${#found[@]} -eq 0 ]]; then
         die "merge: no shard files ${prefix}.shard_*_of_*.h5 (prefix from ${deck}; --prefix to set it)"
      elif [[ ${#found[@]} -gt 1 ]]; then
         die "merge: shard files of ${#found[@]} shard counts (${found[*]}) under ${prefix}: give --shards N"
      fi
      shards=${found[0]}
   fi
   files=()
   missing=()
   for ((i = 1; i <= shards; i++)); do
      f="${prefix}.shard_${i}_of_${shards}"
      if [[ -f ${f}.h5 ]]; then
         files+=("${f}.h5")
      elif [[ -f ${f}.checkpoint ]]; then
         missing+=("${i} (interrupted: ${f}.checkpoint is there, run the shard again)")
      else
         missing+=("${i}")
      fi
   done
   if [[ ${#missing[@]} -gt 0 ]]; then
      printf 'slurm_sweep: merge: %d of %d shard files missing under %s:\n' "${#missing[@]}" \
         "${shards}" "${prefix}" >&2
      printf '  shard %s\n' "${missing[@]}" >&2
      exit 2
   fi
   exe=$(find_gapbeam)
   mkdir -p -- "$(dirname -- "${prefix}")" || die "cannot create the directory of ${prefix}"
   printf 'slurm_sweep: %s merge %s.h5 (%d shard files)\n' "${exe}" "${prefix}" "${shards}"
   status=0
   "${exe}" merge "${prefix}.h5" "${files[@]}" || status=$?
   # 5: merged, but the shards hold failed points (marked in the file): plot, then return 5
   if [[ ${status} -ne 0 && ${status} -ne 5 ]]; then
      printf 'slurm_sweep: merge failed with status %d\n' "${status}" >&2
      exit "${status}"
   fi
   plot=${root}/scripts/plot.sh
   if [[ -x ${plot} ]] && command -v gnuplot >/dev/null 2>&1; then
      "${plot}" sweep "${prefix}" || printf 'slurm_sweep: warning: plotting %s failed\n' "${prefix}" >&2
   fi
   exit "${status}"
fi

# A shard of the sweep.
if [[ -n ${shards} ]]; then
   count=${shards}
   index=${task_id:-1}
elif [[ -n ${task_id} ]]; then
   count=${SLURM_ARRAY_TASK_COUNT:-$((task_max - task_min + 1))}
   index=$((task_id - task_min + 1))
else
   count=1
   index=1
fi
if ! [[ ${count} =~ ^[1-9][0-9]*$ && ${index} =~ ^[0-9]+$ ]] || ((index < 1 || index > count)); then
   die "shard ${index} of ${count}: need 1 <= I <= N (array task ${task_id:-none}, --shards ${shards:-unset})"
fi

exe=$(find_gapbeam)
# the output directory, before the program opens its checkpoint there (gapbeam makes it too;
# made here so that a deck whose prefix cannot be created fails with a clear line in the log)
out_dir=$(dirname -- "$(deck_prefix)")
mkdir -p -- "${out_dir}" || die "cannot create the output directory ${out_dir}"
args=(--shard "${index}/${count}")
if [[ -n ${shard_costs} ]]; then args+=(--shard-costs "${shard_costs}"); fi
limit=$(task_time_limit)
if [[ -n ${limit} ]]; then args+=(--time-limit "${limit}"); fi
printf 'slurm_sweep: %s on %s: shard %d of %d, OMP_NUM_THREADS=%s, time limit %s\n' \
   "$(date '+%Y-%m-%d %H:%M:%S')" "$(hostname)" "${index}" "${count}" "${OMP_NUM_THREADS}" \
   "${limit:-none}${limit:+ s}"
printf 'slurm_sweep: %s %s %s%s\n' "${exe}" "${deck}" "${args[*]}" "${overrides[*]+ ${overrides[*]}}"
# The program runs as a child that the script waits for, so that a SIGTERM (Slurm's signal at
# the time limit, on preemption and on scancel) reaches the script without ending it: the
# program, which Slurm signals too, finishes its chunk, keeps the checkpoint and exits with 3;
# outside Slurm the script passes the signal on (and Ctrl-C as SIGTERM: a child started in the
# background ignores SIGINT). A task stopped so is not requeued here.
got_term=0
"${exe}" "${deck}" "${args[@]}" "${overrides[@]+"${overrides[@]}"}" &
child=$!
on_term() {
   got_term=1
   if [[ -z ${SLURM_JOB_ID:-} ]]; then kill -TERM "${child}" 2>/dev/null || true; fi
}
trap on_term TERM
trap 'got_term=1; kill -TERM "${child}" 2>/dev/null || true' INT
while :; do
   status=0
   wait "${child}" || status=$?
   if ((status > 128)) && kill -0 "${child}" 2>/dev/null; then continue; fi   # the trap ran
   break
done
trap - TERM INT

if [[ ${status} -eq 3 && ${got_term} -eq 1 ]]; then
   printf 'slurm_sweep: shard %d of %d stopped by SIGTERM (scancel, preemption or the job time limit); its checkpoint is kept: run the same shard again to finish (not requeued here)\n' \
      "${index}" "${count}" >&2
elif [[ ${status} -eq 3 ]]; then
   printf 'slurm_sweep: shard %d of %d reached the time limit; its checkpoint is kept: run the same shard again to finish\n' \
      "${index}" "${count}" >&2
   if [[ ${GAPBEAM_AUTO_REQUEUE:-0} == 1 && -n ${SLURM_JOB_ID:-} ]]; then
      restarts=${SLURM_RESTART_COUNT:-0}
      if ((restarts < ${GAPBEAM_MAX_REQUEUE:-10})); then
         job=${SLURM_JOB_ID}
         if [[ -n ${SLURM_ARRAY_JOB_ID:-} && -n ${task_id} ]]; then job=${SLURM_ARRAY_JOB_ID}_${task_id}; fi
         printf 'slurm_sweep: requeueing %s (restart %d)\n' "${job}" "$((restarts + 1))" >&2
         scontrol requeue "${job}" || printf 'slurm_sweep: scontrol requeue %s failed\n' "${job}" >&2
      else
         printf 'slurm_sweep: not requeued: %d restarts already (GAPBEAM_MAX_REQUEUE)\n' "${restarts}" >&2
      fi
   fi
elif [[ ${status} -ne 0 ]]; then
   printf 'slurm_sweep: gapbeam exited with status %d\n' "${status}" >&2
fi
exit "${status}"
