#!/usr/bin/env bash
# scripts/test_slurm.sh - the Slurm campaign of docs/running.md against a real Slurm.
#
# Usage:
#   scripts/test_slurm.sh        (scripts/test.sh runs it; it needs root or sudo for apt-get
#                                 when Slurm is not installed yet)
#
# What it does (docs/running.md, "Testing against Slurm", says the same for users):
#   1. installs Debian's Slurm where missing (`scripts/setup.sh --slurm`: slurmctld slurmd
#      slurm-client slurmdbd munge mariadb-server), within GAPBEAM_SLURM_INSTALL_TIMEOUT seconds
#      (default 900), and builds the release profile (`fpm build --profile release`);
#   2. writes a single-node configuration into a temporary folder: all the machine's cores (the
#      NodeName line of `slurmd -C`), a partition with MaxTime 30 minutes, free ports on
#      127.0.0.1, state, spool, logs, munge key and socket and the accounting database all in
#      that folder, the daemons run as the current user; accounting through slurmdbd and a
#      private mariadbd, since sacct needs slurmdbd (Slurm 22.05 has no file-based accounting
#      storage, and jobcomp/filetxt records no CPU time);
#   3. starts munged, mariadbd, slurmdbd, slurmctld and slurmd as its own processes (in the
#      foreground modes, as children of this script) and stops them by their process ids at the
#      end, also on failure or interruption (trap), after cancelling the jobs left;
#   4. copies the working tree (tracked and untracked files, and build/) into the temporary
#      folder, writes two small sweep decks there, and runs the blocks of docs/running.md marked
#      `<!-- test_slurm.sh: campaign -->` and `<!-- test_slurm.sh: recover -->` exactly as written
#      but for their settings lines (`name=value`), in a fresh bash from that copy's root, with
#      GAPBEAM* and OMP_NUM_THREADS unset (a new user's shell; SLURM_CONF points at the test's
#      configuration, as /etc/slurm/slurm.conf would on a cluster);
#   5. checks campaigns A (a 20-point deck in 4 shards: merge waits, merged file = single-process
#      sweep bitwise, sacct CPU times), B (about 90 s of work in 2 shards, sized from the measured
#      cost of a point, walltime 1 minute: each task stops at its time limit with status 3,
#      requeues itself, resumes from its checkpoint, same result) and C (A's deck in 2 shards:
#      task 2 cancelled by scancel after its first checkpointed points, the merge waits in vain
#      and a merge without the dependency refuses, the recovery block completes the campaign,
#      same result).
# The single-process reference of each deck is run with the same release executable, in
# another folder with the same relative output prefix (so that /deck and /run/files agree).
# "Bitwise on every dataset": every dataset and attribute of the two files is compared byte for
# byte (h5py), except the per-point CPU times (/sweep/seconds, /sweep/seconds_label,
# /sweep/seconds_certify), the root attribute creation_time, and /run/cpu_seconds,
# /run/wall_seconds and /run/threads, which a merged file does not have.
#
# Prints `PASS  slurm: ...` / `FAIL  slurm: ...` per check, NOTE lines with what was measured,
# then `test_slurm.sh: S s` and `N passed, N failed`; exit status 1 if a check failed. When Slurm
# cannot be installed or started it prints `NOTE  slurm: skipped: <why>` and `0 passed, 0 failed`
# (exit 0), unless GAPBEAM_SLURM_REQUIRED=1 (or true), which makes that one failure.
#
# Environment: GAPBEAM_SLURM_REQUIRED (above), GAPBEAM_SLURM_INSTALL_TIMEOUT (above),
# GAPBEAM_SLURM_KEEP=1 keeps the temporary folder (its path is printed).
set -uo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
required=${GAPBEAM_SLURM_REQUIRED:-0}
[[ ${required} == true ]] && required=1
t_start=$(date +%s)
n_pass=0
n_fail=0
T=''
pids=()        # daemons started here, in start order
names=()

if [[ ${1:-} == -h || ${1:-} == --help ]]; then
   sed -n '2,/^set -uo/{/^set -uo/d;s/^# \{0,1\}//;p}' "${BASH_SOURCE[0]}"
   exit 0
fi

pass() { printf 'PASS  slurm: %s\n' "$1"; n_pass=$((n_pass + 1)); }
fail() { printf 'FAIL  slurm: %s\n' "$1"; n_fail=$((n_fail + 1)); }
note() { printf 'NOTE  slurm: %s\n' "$1"; }
# check NAME [WHY ...]: PASS without WHY, else FAIL with the reasons
check() {
   local name=$1
   shift
   if [[ $# -eq 0 ]]; then pass "${name}"; else fail "${name} ($(printf '%s; ' "$@" | sed 's/; $//'))"; fi
}

finish() {
   cleanup
   printf 'test_slurm.sh: %d s\n' "$(($(date +%s) - t_start))"
   printf '%d passed, %d failed\n' "${n_pass}" "${n_fail}"
   [[ ${n_fail} -eq 0 ]] && exit 0
   exit 1
}

# Not a failure (unless required): Slurm could not be had here.
skip() {
   if [[ ${required} == 1 ]]; then
      fail "Slurm could not be set up: $1"
   else
      note "skipped: $1"
   fi
   finish
}

# The last lines of a log, indented.
show_log() {
   [[ -f $1 ]] || return 0
   printf '    --- last lines of %s\n' "$1"
   tail -n "${2:-15}" "$1" | sed 's/^/    /'
}

# Cancel the test's jobs, stop the daemons by pid (the last started first), remove the folder.
cleanup() {
   local i pid k
   trap - EXIT INT TERM
   if [[ ${#pids[@]} -gt 0 ]] && [[ -n ${SLURM_CONF:-} ]] && command -v scancel >/dev/null; then
      timeout 10 scancel --user="$(id -un)" >/dev/null 2>&1 || true
      for ((k = 0; k < 40; k++)); do
         [[ -z $(timeout 5 squeue -h 2>/dev/null) ]] && break
         sleep 1
      done
   fi
   for ((i = ${#pids[@]} - 1; i >= 0; i--)); do
      pid=${pids[i]}
      kill -TERM "${pid}" 2>/dev/null || continue
      for ((k = 0; k < 100; k++)); do
         kill -0 "${pid}" 2>/dev/null || break
         sleep 0.1
      done
      kill -KILL "${pid}" 2>/dev/null || true
      wait "${pid}" 2>/dev/null || true
   done
   pids=()
   if [[ -n ${T} && -d ${T} ]]; then
      if [[ ${GAPBEAM_SLURM_KEEP:-0} == 1 ]]; then
         note "kept ${T}"
      else
         rm -rf "${T}"
      fi
   fi
}
trap 'cleanup' EXIT
trap 'cleanup; exit 130' INT
trap 'cleanup; exit 143' TERM

# start NAME COMMAND...: a daemon in the foreground mode, as a child; its log is T/log/NAME.out
start() {
   local name=$1
   shift
   "$@" </dev/null >"${T}/log/${name}.out" 2>&1 &
   pids+=($!)
   names+=("${name}")
}

# wait_for SECONDS COMMAND...: true once COMMAND succeeds (every 0.5 s), false at the deadline
# or when the last daemon started has died.
wait_for() {
   local limit=$1 t0
   shift
   t0=$(date +%s)
   while (($(date +%s) - t0 < limit)); do
      "$@" >/dev/null 2>&1 && return 0
      kill -0 "${pids[-1]}" 2>/dev/null || return 1
      sleep 0.5
   done
   return 1
}

# ---- 1. Slurm installed, the release build ----------------------------------------------------
export PATH="${PATH}:/usr/sbin:/sbin"
if ! timeout "${GAPBEAM_SLURM_INSTALL_TIMEOUT:-900}" bash "${root}/scripts/setup.sh" --slurm; then
   skip "installing Slurm (scripts/setup.sh --slurm) failed or took longer than ${GAPBEAM_SLURM_INSTALL_TIMEOUT:-900} s"
fi
# shellcheck source=setup.sh
source "${root}/scripts/setup.sh" >/dev/null || skip 'scripts/setup.sh failed'
for c in munged munge mariadbd mariadb-install-db mariadb slurmdbd slurmctld slurmd sbatch squeue \
         scontrol sacct sacctmgr scancel python3; do
   command -v "${c}" >/dev/null 2>&1 || skip "${c} is missing after scripts/setup.sh --slurm"
done
python3 -c 'import h5py' 2>/dev/null || skip 'python3 cannot import h5py'
printf '== fpm build --profile release\n'
if ! (cd "${root}" && fpm build --profile release >/dev/null 2>&1); then
   fail 'fpm build --profile release failed in the repository'
   finish
fi

# ---- 2. the configuration ---------------------------------------------------------------------
T=$(mktemp -d "${TMPDIR:-/tmp}/gapbeam-slurm-XXXXXX")
chmod 755 "${T}"        # munged wants every folder above its socket searchable by all
mkdir -p "${T}/munge" "${T}/munge-run" "${T}/etc" "${T}/state" "${T}/spool" "${T}/log" \
   "${T}/db" "${T}/repo" "${T}/ref"
chmod 700 "${T}/munge"
chmod 755 "${T}/munge-run"
me=$(id -un)
host=$(hostname -s)
mapfile -t ports < <(python3 -c 'import socket
ss = [socket.socket() for _ in range(4)]
for s in ss: s.bind(("127.0.0.1", 0))
for s in ss: print(s.getsockname()[1])')
[[ ${#ports[@]} -eq 4 ]] || skip 'no free ports on 127.0.0.1'
p_ctld=${ports[0]}; p_d=${ports[1]}; p_db=${ports[2]}; p_dbd=${ports[3]}
node_line=$(slurmd -C 2>/dev/null | grep '^NodeName=' | sed -E "s/^NodeName=[^ ]+//; s/ RealMemory=[0-9]+//")
[[ -n ${node_line} ]] || skip 'slurmd -C does not describe this node'
cores=$(sed -E 's/.*CPUs=([0-9]+).*/\1/' <<<"${node_line}")
sock=${T}/munge-run/munge.socket
cat >"${T}/etc/slurm.conf" <<EOF
# single-node test cluster of scripts/test_slurm.sh
ClusterName=gapbeamtest
SlurmctldHost=${host}(127.0.0.1)
SlurmUser=${me}
SlurmdUser=${me}
SlurmctldPort=${p_ctld}
SlurmdPort=${p_d}
AuthType=auth/munge
AuthInfo=socket=${sock}
CredType=cred/munge
StateSaveLocation=${T}/state
SlurmdSpoolDir=${T}/spool
SlurmctldPidFile=${T}/slurmctld.pid
SlurmdPidFile=${T}/slurmd.pid
SlurmctldLogFile=${T}/log/slurmctld.log
SlurmdLogFile=${T}/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
JobAcctGatherType=jobacct_gather/linux
JobAcctGatherFrequency=5
AccountingStorageType=accounting_storage/slurmdbd
AccountingStorageHost=127.0.0.1
AccountingStoragePort=${p_dbd}
AccountingStoragePass=${sock}
JobCompType=jobcomp/none
SchedulerType=sched/builtin
SchedulerParameters=sched_interval=2
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
KillWait=30
MinJobAge=600
NodeName=${host} NodeAddr=127.0.0.1 ${node_line} State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=30 State=UP
EOF
cat >"${T}/etc/slurmdbd.conf" <<EOF
AuthType=auth/munge
AuthInfo=socket=${sock}
DbdHost=${host}
DbdAddr=127.0.0.1
DbdPort=${p_dbd}
SlurmUser=${me}
LogFile=${T}/log/slurmdbd.log
PidFile=${T}/slurmdbd.pid
StorageType=accounting_storage/mysql
StorageHost=127.0.0.1
StoragePort=${p_db}
StorageUser=root
StorageLoc=gapbeam_slurm_acct
EOF
chmod 600 "${T}/etc/slurmdbd.conf"
export SLURM_CONF=${T}/etc/slurm.conf

# ---- 3. the daemons ---------------------------------------------------------------------------
t_daemons=$(date +%s)
head -c 1024 /dev/urandom >"${T}/munge/munge.key"
chmod 400 "${T}/munge/munge.key"
start munged munged --foreground --key-file="${T}/munge/munge.key" --socket="${sock}" \
   --pid-file="${T}/munge-run/munged.pid" --log-file="${T}/munge/munged.log" \
   --seed-file="${T}/munge/munged.seed"
if ! wait_for 20 bash -c "munge -S '${sock}' -n | unmunge -S '${sock}'"; then
   show_log "${T}/log/munged.out"; show_log "${T}/munge/munged.log"
   skip 'munged did not start'
fi
if ! timeout 120 mariadb-install-db --no-defaults --datadir="${T}/db" --user="${me}" \
      --auth-root-authentication-method=normal --skip-test-db --skip-name-resolve \
      --innodb-log-file-size=8M >"${T}/log/mariadb-install-db.out" 2>&1; then
   show_log "${T}/log/mariadb-install-db.out"
   skip 'mariadb-install-db failed'
fi
start mariadbd mariadbd --no-defaults --user="${me}" --datadir="${T}/db" \
   --socket="${T}/mysql.sock" --port="${p_db}" --bind-address=127.0.0.1 --skip-grant-tables \
   --skip-name-resolve --skip-log-bin --innodb-buffer-pool-size=32M --innodb-log-file-size=8M \
   --pid-file="${T}/mariadbd.pid" --log-error="${T}/log/mariadbd.err"
if ! wait_for 60 mariadb --no-defaults --socket="${T}/mysql.sock" -e 'select 1'; then
   show_log "${T}/log/mariadbd.err"
   skip 'mariadbd did not start'
fi
start slurmdbd slurmdbd -D
if ! wait_for 60 sacctmgr -i add cluster gapbeamtest; then
   show_log "${T}/log/slurmdbd.log"
   skip 'slurmdbd did not start (sacctmgr add cluster failed)'
fi
start slurmctld slurmctld -D -i
if ! wait_for 30 scontrol ping; then
   show_log "${T}/log/slurmctld.log"
   skip 'slurmctld did not start'
fi
start slurmd slurmd -D
if ! wait_for 60 bash -c '[[ $(sinfo -h -N -o %T 2>/dev/null) == idle ]]'; then
   show_log "${T}/log/slurmd.log"; show_log "${T}/log/slurmctld.log"
   skip 'slurmd did not start (the node is not idle)'
fi
note "daemons up in $(($(date +%s) - t_daemons)) s: munged, mariadbd, slurmdbd, slurmctld, slurmd (pids ${pids[*]}), node ${host} with ${cores} CPUs, Slurm $(sinfo -V 2>/dev/null | awk '{print $2}')"

# ---- 4. the copy of the repository, the decks, the references ---------------------------------
if git -C "${root}" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
   (cd "${root}" && git ls-files -co --exclude-standard -z | tar --null -T - -cf - 2>/dev/null) \
      | tar -xf - -C "${T}/repo"
else
   (cd "${root}" && tar --exclude=./build --exclude=./results -cf - .) | tar -xf - -C "${T}/repo"
fi
[[ -d ${root}/build ]] && cp -a "${root}/build" "${T}/repo/build"
mkdir -p "${T}/repo/slurm_test"
# decks of points of about 0.7 s each (release build): 32768 fixed steps per forcing period;
# chunks of 2 points (both threads of the reference busy, a checkpoint every 1.5 s in a task)
model=$(sed -n '/^&beam/,/^&forcing/p' "${root}/test/decks/sweep_small.nml" | sed '$d')
write_deck() {   # write_deck NAME OUTPUT SWEEP_LINE
   cat >"${T}/repo/slurm_test/$1.nml" <<EOF
! scripts/test_slurm.sh: the reference beam of test/decks/sweep_small.nml, zero gap
&job analysis = 'sweep', title = 'Slurm test sweep $1', output = '$2' /
${model}
&forcing frequency_hz = 10.0, amplitude_pp = 4.0e-3 /
&solver step_control = 'fixed', steps_per_period = 32768, transient_periods = 60,
        record_periods = 40 /
&diagnostics lyapunov_periods = 20, lyapunov_max_periods = 40, certify = .false. /
$3
EOF
}
write_deck mid results/slurm_mid "&sweep mode = 'independent', frequency_start_hz = 9.6, frequency_end_hz = 10.5, n_frequency = 10,
       amplitude_pp = 2.0e-3, 4.0e-3, progress = .false., chunk = 2 /"
exe=$(cd "${T}/repo" && fpm run --profile release --runner echo gapbeam 2>/dev/null | tail -n 1)
[[ ${exe} == /* ]] || exe=${T}/repo/${exe}
if [[ ! -x ${exe} ]]; then
   fail "the copy's release executable is not there (${exe})"
   finish
fi
# reference run R DECK: the single-process sweep, in ref/ (same relative output prefix)
reference() {
   local d=$1 t0
   t0=$(date +%s)
   if ! (cd "${T}/ref" && OMP_NUM_THREADS=${cores} OPENBLAS_NUM_THREADS=1 GAPBEAM_GIT_COMMIT=unknown \
         "${exe}" "${T}/repo/slurm_test/${d}.nml" --quiet >"${T}/log/ref_${d}.out" 2>&1); then
      show_log "${T}/log/ref_${d}.out"
      fail "the single-process reference sweep of ${d}.nml failed"
      finish
   fi
   note "reference: slurm_test/${d}.nml in one process (${cores} threads): $(($(date +%s) - t0)) s wall, $(grep -o '^cpu: [^,]*' "${T}/log/ref_${d}.out")"
}
reference mid
# campaign B's deck: about 45 s of work per shard on this machine (the mid deck's CPU time per
# point tells), so that the first run of each task (time limit about 30 s from its 1-minute
# walltime) stops with work left, and the second (another 30 s) finishes it
per_point=$(awk '/^cpu: / {print $2 / 20; exit}' "${T}/log/ref_mid.out")
n_slow=$(python3 -c "import math, sys; print(min(250, max(8, math.ceil(2 * 45.0 / 4 / float(sys.argv[1])))))" "${per_point:-0.7}")
write_deck slow results/slurm_slow "&sweep mode = 'independent', frequency_start_hz = 9.0, frequency_end_hz = 11.0, n_frequency = ${n_slow},
       amplitude_pp = 2.0e-3, 3.0e-3, 4.0e-3, 5.0e-3, progress = .false., chunk = 2 /"
note "campaign B's deck: ${n_slow} x 4 points (${per_point} s CPU a point in the reference)"
reference slow

# Compare a merged file with its reference, dataset by dataset, byte for byte.
compare() {   # compare NAME (results/NAME.h5 in the copy and in ref/)
   python3 - "${T}/repo/results/$1.h5" "${T}/ref/results/$1.h5" <<'PY'
import sys
import h5py
skip_differ = {'/sweep/seconds', '/sweep/seconds_label', '/sweep/seconds_certify'}
only_ref = {'/run/cpu_seconds', '/run/wall_seconds', '/run/threads'}
def items(f):
    out = {}
    f.visititems(lambda n, o: out.__setitem__('/' + n, o))
    out['/'] = f
    return out
def raw(x):
    return x.tobytes() if hasattr(x, 'tobytes') else repr(x).encode()
bad = []
with h5py.File(sys.argv[1], 'r') as a, h5py.File(sys.argv[2], 'r') as b:
    ia, ib = items(a), items(b)
    for n in sorted(set(ib) - set(ia) - only_ref):
        bad.append('missing in the merged file: ' + n)
    for n in sorted(set(ia) - set(ib)):
        bad.append('only in the merged file: ' + n)
    n_data = 0
    for n in sorted(set(ia) & set(ib)):
        x, y = ia[n], ib[n]
        if isinstance(x, h5py.Dataset):
            n_data += 1
            if n not in skip_differ and (x.dtype != y.dtype or x.shape != y.shape
                                         or raw(x[()]) != raw(y[()])):
                bad.append('differs: ' + n)
        for k in sorted(set(x.attrs) | set(y.attrs)):
            if n == '/' and k == 'creation_time':
                continue
            if k not in x.attrs or k not in y.attrs or raw(x.attrs[k]) != raw(y.attrs[k]):
                bad.append('attribute differs: {} {}'.format(n, k))
if bad:
    print('; '.join(bad[:8]) + (' ...' if len(bad) > 8 else ''))
    sys.exit(1)
print('{} datasets and their attributes equal'.format(n_data))
PY
}

# run_block BLOCK OUT [name=value ...] [-- PRELUDE_LINE ...]: the block of docs/running.md marked
# `<!-- test_slurm.sh: BLOCK -->`, its settings lines replaced by the values given, after the
# prelude lines, run by a fresh bash in the copy's root; its output in OUT. False when a setting
# is missing from the block or the block fails.
run_block() {
   local block=$1 out=$2 kv name script=${T}/${1}_$$_${RANDOM}.sh
   shift 2
   local -a sets=() prelude=()
   while [[ $# -gt 0 && $1 != -- ]]; do sets+=("$1"); shift; done
   [[ ${1:-} == -- ]] && shift
   prelude=("$@")
   awk -v m="<!-- test_slurm.sh: ${block} -->" '
      $0 == m { want = 1; next }
      want && /^```sh/ { inside = 1; next }
      inside && /^```/ { exit }
      inside { print }' "${root}/docs/running.md" >"${script}.block"
   if [[ ! -s ${script}.block ]]; then
      printf 'no block <!-- test_slurm.sh: %s --> in docs/running.md\n' "${block}" >"${out}"
      return 1
   fi
   for kv in "${sets[@]}"; do
      name=${kv%%=*}
      if ! grep -q "^${name}=" "${script}.block"; then
         printf 'the block %s has no setting %s=\n' "${block}" "${name}" >"${out}"
         return 1
      fi
      KV=${kv} NAME=${name} awk 'BEGIN { n = ENVIRON["NAME"]; kv = ENVIRON["KV"] }
         index($0, n "=") == 1 { sub(/^[^ #]*/, kv) } { print }' "${script}.block" >"${script}.tmp"
      mv "${script}.tmp" "${script}.block"
   done
   { printf 'set -e\n'; printf '%s\n' "${prelude[@]+"${prelude[@]}"}"; cat "${script}.block"; } \
      >"${script}"
   (cd "${T}/repo" && env -u GAPBEAM -u GAPBEAM_AUTO_REQUEUE -u GAPBEAM_GIT_COMMIT \
      -u GAPBEAM_TIME_LIMIT -u GAPBEAM_TIME_MARGIN -u GAPBEAM_SHARD_COSTS -u OMP_NUM_THREADS \
      bash "${script}") >"${out}" 2>&1
}

# wait_jobs SECONDS JOBID...: until none of the jobs is in squeue; a task held after its requeue
# (Slurm keeps it PENDING, reason BeginTime, for about two minutes) is released with
# `scontrol update StartTime=now` once it has been held 5 s: the run before must be gone from the
# node first (its clean-up removes the task's spool folder; a release within the same second
# started the next run there and lost its script: FAILED 1:0 with an empty log). False at the
# deadline.
declare -A held_since=()
wait_jobs() {
   local limit=$1 t0 id reason ids q now
   shift
   t0=$(date +%s)
   ids=$(IFS=,; echo "$*")
   while (($(date +%s) - t0 < limit)); do
      q=$(squeue -h -j "${ids}" -o '%i %T %r' 2>/dev/null)
      [[ -z ${q} ]] && return 0
      now=$(date +%s)
      while read -r id _ reason; do
         [[ ${reason} == BeginTime ]] || continue
         [[ -n ${held_since[${id}]:-} ]] || held_since[${id}]=${now}
         if ((now - held_since[${id}] >= 5)); then
            scontrol update JobId="${id}" StartTime=now >/dev/null 2>&1 && released+=("${id}")
            unset 'held_since[${id}]'
         fi
      done <<<"${q}"
      sleep 1
   done
   return 1
}

# sacct_rows JOBID FIELDS [-D]: `sacct -X -n -P -o JobID,State,FIELDS` lines (-D: every run of a
# requeued job). Waits up to 30 s until no row is pending, running or completing: the records
# reach slurmdbd a moment after the job ends.
sacct_rows() {
   local id=$1 fields=$2 k rows
   local -a extra=()
   [[ ${3:-} == -D ]] && extra=(-D)
   for ((k = 0; k < 60; k++)); do
      rows=$(sacct -j "${id}" -X -n -P "${extra[@]+"${extra[@]}"}" -o "JobID,State,${fields}" 2>/dev/null)
      if [[ -n ${rows} ]] && ! awk -F'|' '$2 ~ /^(PENDING|RUNNING|COMPLETING)$/ { f = 1 } END { exit !f }' <<<"${rows}"; then
         break
      fi
      sleep 0.5
   done
   printf '%s\n' "${rows}"
}

# Seconds in sacct's TotalCPU ([DD-][HH:]MM:SS[.mmm]).
cpu_seconds() {
   python3 -c 'import sys
t = sys.argv[1]; d = 0
if "-" in t: d, t = t.split("-"); d = int(d)
p = [float(x) for x in t.split(":")]
while len(p) < 3: p.insert(0, 0.0)
print(d * 86400 + p[0] * 3600 + p[1] * 60 + p[2])' "$1"
}

# Unix time of a sacct time stamp.
epoch() { date -d "$1" +%s 2>/dev/null || echo 0; }

logs=${T}/repo/logs
task_log() { printf '%s/gapbeam-sweep_%s_%s.out' "${logs}" "$1" "$2"; }
released=()

# ---- 5a. campaign A: the recipe as written, 4 shards ------------------------------------------
printf '== campaign A: slurm_test/mid.nml, 4 shards, throttle 2\n'
t0=$(date +%s)
why=()
run_block campaign "${T}/log/campaign_A.out" deck=slurm_test/mid.nml shards=4 throttle=2 \
   threads=1 walltime=00:05:00 || why+=("the recipe failed: $(tail -n 3 "${T}/log/campaign_A.out" | tr '\n' ' ')")
ids=$(grep -o 'sweep: array job [0-9]*, merge: job [0-9]*' "${T}/log/campaign_A.out" | tail -n 1)
jid=$(awk '{print $4}' <<<"${ids}" | tr -d ,)
mid=$(awk '{print $7}' <<<"${ids}")
[[ -n ${jid} && -n ${mid} ]] || why+=('no job ids printed')
check "campaign A: the recipe of docs/running.md submits the array and the merge (jobs ${jid:-?}, ${mid:-?})" "${why[@]}"
if [[ -n ${jid} && -n ${mid} ]]; then
   for ((k = 0; k < 20; k++)); do     # until the controller has looked at the dependency
      reason=$(squeue -h -j "${mid}" -o '%T %r' 2>/dev/null)
      n_tasks_left=$(squeue -h -j "${jid}" 2>/dev/null | grep -c '' || true)
      [[ ${reason} == 'PENDING None' ]] || break
      sleep 0.25
   done
   why=()
   [[ ${reason} == 'PENDING Dependency' ]] || why+=("merge state '${reason}' right after submission")
   [[ ${n_tasks_left} -gt 0 ]] || why+=('the array had already ended')
   check "campaign A: the merge waits for the array (PENDING (Dependency) while ${n_tasks_left} task(s) pending or running)" "${why[@]}"
   wait_jobs 300 "${jid}" "${mid}" || fail 'campaign A: the jobs did not end within 300 s'
   note "campaign A: ended $(($(date +%s) - t0)) s after submission"
   rows=$(sacct_rows "${jid}" 'ExitCode,Start,End')
   why=()
   [[ $(grep -c '|COMPLETED|0:0|' <<<"${rows}") -eq 4 ]] || why+=("sacct: $(tr '\n' ' ' <<<"${rows}")")
   last_end=0
   while IFS='|' read -r id state code start end; do
      [[ -n ${id} ]] || continue
      e=$(epoch "${end}"); ((e > last_end)) && last_end=${e}
   done <<<"${rows}"
   # TotalCPU: the job's steps (the allocation rows of `sacct -X` show 0); one batch step a task
   cpu_line=''
   n_cpu=0
   while IFS='|' read -r id cpu elapsed; do
      [[ ${id} == *.batch ]] || continue
      n_cpu=$((n_cpu + 1))
      s=$(cpu_seconds "${cpu}")
      python3 -c "import sys; sys.exit(0 if float('${s}') > 0 else 1)" || why+=("task ${id}: TotalCPU ${cpu}")
      cpu_line+="${id%.batch} ${cpu} CPU in ${elapsed}; "
   done < <(sacct -j "${jid}" -n -P -o JobID,TotalCPU,Elapsed 2>/dev/null)
   [[ ${n_cpu} -eq 4 ]] || why+=("sacct lists ${n_cpu} batch steps, want 4")
   check 'campaign A: every task COMPLETED with status 0, and sacct shows its CPU time (TotalCPU > 0)' "${why[@]}"
   note "sacct -j ${jid} -o JobID,TotalCPU,Elapsed (batch steps): ${cpu_line%; }"
   mrow=$(sacct_rows "${mid}" 'ExitCode,Start' | head -n 1)
   why=()
   [[ ${mrow} == *'|COMPLETED|0:0|'* ]] || why+=("merge: ${mrow}")
   m_start=$(epoch "${mrow##*|}")
   ((m_start >= last_end && last_end > 0)) || why+=("merge started at ${mrow##*|}, before the last task ended")
   grep -q 'merged 4 shard files into results/slurm_mid.h5' "$(task_log "${mid}" 1)" 2>/dev/null \
      || why+=('the merge log lacks "merged 4 shard files"')
   check 'campaign A: the merge ran after the last task ended, and merged the 4 shard files' "${why[@]}"
   msg=$(compare slurm_mid 2>&1)
   st=$?
   why=()
   [[ ${st} -eq 0 ]] || why+=("${msg}")
   check "campaign A: the merged file equals the single-process sweep bitwise (${msg})" "${why[@]}"
fi
mkdir -p "${T}/campaign_A"
mv "${T}"/repo/results/slurm_mid* "${T}/campaign_A/" 2>/dev/null

# ---- 5b. campaign B: time limit, requeue, resume ----------------------------------------------
printf '== campaign B: slurm_test/slow.nml, 2 shards, walltime 1 minute\n'
t0=$(date +%s)
why=()
released=()
run_block campaign "${T}/log/campaign_B.out" deck=slurm_test/slow.nml shards=2 throttle=2 \
   threads=1 walltime=00:01:00 || why+=("the recipe failed: $(tail -n 3 "${T}/log/campaign_B.out" | tr '\n' ' ')")
ids=$(grep -o 'sweep: array job [0-9]*, merge: job [0-9]*' "${T}/log/campaign_B.out" | tail -n 1)
jid=$(awk '{print $4}' <<<"${ids}" | tr -d ,)
mid=$(awk '{print $7}' <<<"${ids}")
[[ -n ${jid} && -n ${mid} ]] || why+=('no job ids printed')
check "campaign B: the recipe submits a 2-task array with --time=00:01:00 and the merge (jobs ${jid:-?}, ${mid:-?})" "${why[@]}"
if [[ -n ${jid} && -n ${mid} ]]; then
   wait_jobs 420 "${jid}" "${mid}" || fail 'campaign B: the jobs did not end within 420 s'
   note "campaign B: ended $(($(date +%s) - t0)) s after submission; held requeued tasks released: ${released[*]:-none}"
   for i in 1 2; do
      log=$(task_log "${jid}" "${i}")
      why=()
      grep -q 'sweep: time limit reached after' "${log}" 2>/dev/null || why+=('no "time limit reached" in its log')
      grep -q "slurm_sweep: requeueing ${jid}_${i} (restart 1)" "${log}" 2>/dev/null || why+=('no "requeueing" in its log')
      loaded=$(grep -o ' [0-9]* already in the checkpoint' "${log}" 2>/dev/null | awk '{print $1}' | sort -n | tail -n 1)
      [[ ${loaded:-0} -gt 0 ]] || why+=('no run loaded points from the checkpoint')
      runs=$(sacct_rows "${jid}_${i}" 'ExitCode' -D)
      grep -q '|REQUEUED|' <<<"${runs}" || why+=("sacct -D shows no REQUEUED run: $(tr '\n' ' ' <<<"${runs}")")
      [[ $(tail -n 1 <<<"${runs}") == *'|COMPLETED|0:0' ]] || why+=("last run: $(tail -n 1 <<<"${runs}")")
      limit=$(grep -o 'time limit [0-9]* s' "${log}" 2>/dev/null | head -n 1)
      check "campaign B: task ${i} stopped at its time limit (${limit:-?} from --time=00:01:00, status 3), requeued itself, resumed with ${loaded:-0} points from its checkpoint, COMPLETED" "${why[@]}"
      [[ ${#why[@]} -eq 0 ]] || show_log "${log}" 40
   done
   mrow=$(sacct_rows "${mid}" 'ExitCode' | head -n 1)
   msg=$(compare slurm_slow 2>&1)
   st=$?
   why=()
   [[ ${mrow} == *'|COMPLETED|0:0' ]] || why+=("merge: ${mrow}")
   [[ ${st} -eq 0 ]] || why+=("${msg}")
   check "campaign B: after the requeues the merged file still equals the single-process sweep bitwise (${msg})" "${why[@]}"
fi

# ---- 5c. campaign C: scancel, the merge waits and refuses, the recovery block ------------------
printf '== campaign C: slurm_test/mid.nml, 2 shards, task 2 cancelled\n'
t0=$(date +%s)
why=()
run_block campaign "${T}/log/campaign_C.out" deck=slurm_test/mid.nml shards=2 throttle=2 \
   threads=1 walltime=00:05:00 || why+=("the recipe failed: $(tail -n 3 "${T}/log/campaign_C.out" | tr '\n' ' ')")
ids=$(grep -o 'sweep: array job [0-9]*, merge: job [0-9]*' "${T}/log/campaign_C.out" | tail -n 1)
jid=$(awk '{print $4}' <<<"${ids}" | tr -d ,)
mid=$(awk '{print $7}' <<<"${ids}")
[[ -n ${jid} && -n ${mid} ]] || why+=('no job ids printed')
check "campaign C: the recipe submits a 2-task array and the merge (jobs ${jid:-?}, ${mid:-?})" "${why[@]}"
if [[ -n ${jid} && -n ${mid} ]]; then
   ck=${T}/repo/results/slurm_mid.shard_2_of_2.checkpoint
   has_record() {   # the checkpoint holds at least one record after its header
      python3 -c 'import struct, sys, os
b = open(sys.argv[1], "rb").read()
_, n = struct.unpack_from("<qq", b, 20)
sys.exit(0 if len(b) > 36 + n + 24 else 1)' "${ck}" 2>/dev/null
   }
   k=0
   until has_record || ((k >= 240)); do sleep 0.25; k=$((k + 1)); done
   state=$(squeue -h -j "${jid}_2" -o %T 2>/dev/null)
   scancel "${jid}_2"
   wait_jobs 60 "${jid}" || fail 'campaign C: the array did not end within 60 s of the scancel'
   log2=$(task_log "${jid}" 2)
   why=()
   [[ ${state} == RUNNING ]] || why+=("task 2 was ${state:-gone} when cancelled")
   grep -q 'sweep: stopped by SIGTERM after' "${log2}" 2>/dev/null || why+=('the program did not report SIGTERM')
   grep -q 'stopped by SIGTERM (scancel' "${log2}" 2>/dev/null || why+=('the script did not report SIGTERM')
   grep -q 'requeueing' "${log2}" 2>/dev/null && why+=('the cancelled task requeued itself')
   [[ -f ${ck} ]] || why+=('its checkpoint is gone')
   check 'campaign C: scancel of a running task: the program finishes its chunk, keeps the checkpoint, is not requeued' "${why[@]}"
   k=0
   reason=''
   while ((k < 40)); do
      reason=$(squeue -h -j "${mid}" -o '%T %r' 2>/dev/null)
      [[ ${reason} == *DependencyNeverSatisfied* ]] && break
      sleep 0.5; k=$((k + 1))
   done
   why=()
   [[ ${reason} == 'PENDING DependencyNeverSatisfied' ]] || why+=("state ${reason}")
   check "campaign C: the merge keeps waiting after the cancelled task ('${reason}')" "${why[@]}"
   # a merge submitted without the dependency while shard 2 is missing
   bad=$(cd "${T}/repo" && sbatch --parsable --array=1 --cpus-per-task=1 --time=00:05:00 \
         scripts/slurm_sweep.sh --merge slurm_test/mid.nml 2>&1)
   bad=${bad%%;*}
   wait_jobs 120 "${bad}" || true
   brow=$(sacct_rows "${bad}" 'ExitCode' | head -n 1)
   blog=$(task_log "${bad}" 1)
   why=()
   [[ ${brow} == *'|FAILED|2:0' ]] || why+=("sacct: ${brow}")
   grep -q '1 of 2 shard files missing' "${blog}" 2>/dev/null || why+=('its log does not list the missing shard')
   grep -q 'shard 2 (interrupted: .*checkpoint is there' "${blog}" 2>/dev/null || why+=('its log does not name the checkpoint of shard 2')
   [[ ! -e ${T}/repo/results/slurm_mid.h5 ]] || why+=('a merged file was written')
   check 'campaign C: a merge while shard 2 is missing refuses (FAILED, status 2, naming shard 2 and its checkpoint), writes nothing' "${why[@]}"
   # the recovery block of docs/running.md, as written
   why=()
   run_block recover "${T}/log/recover_C.out" task=2 -- deck=slurm_test/mid.nml shards=2 \
      threads=1 walltime=00:05:00 "mid=${mid}" \
      || why+=("the recovery block failed: $(tail -n 3 "${T}/log/recover_C.out" | tr '\n' ' ')")
   ids=$(grep -o 'shard 2: job [0-9]*, merge: job [0-9]*' "${T}/log/recover_C.out" | tail -n 1)
   jid2=$(awk '{print $4}' <<<"${ids}" | tr -d ,)
   mid2=$(awk '{print $7}' <<<"${ids}")
   [[ -n ${jid2} && -n ${mid2} ]] || why+=('no job ids printed by the recovery block')
   wait_jobs 300 ${jid2:+"${jid2}"} ${mid2:+"${mid2}"} || why+=('the recovery jobs did not end within 300 s')
   if [[ -n ${jid2} ]]; then
      log=$(task_log "${jid2}" 2)
      loaded=$(grep -o ' [0-9]* already in the checkpoint' "${log}" 2>/dev/null | awk '{print $1}' | tail -n 1)
      [[ ${loaded:-0} -gt 0 ]] || why+=('the resubmitted shard loaded no point from its checkpoint')
      [[ $(sacct_rows "${jid2}" 'ExitCode' | head -n 1) == *'|COMPLETED|0:0' ]] || why+=('the resubmitted shard did not complete')
   fi
   old=$(sacct_rows "${mid}" 'ExitCode' | head -n 1)
   [[ ${old} == *'|CANCELLED'* ]] || why+=("the first merge: ${old}")
   msg=$(compare slurm_mid 2>&1)
   st=$?
   [[ ${st} -eq 0 ]] || why+=("${msg}")
   check "campaign C: the recovery block of docs/running.md runs shard 2 again (${loaded:-0} points from its checkpoint) and merges: the merged file equals the single-process sweep bitwise (${msg})" "${why[@]}"
   note "campaign C: ended $(($(date +%s) - t0)) s after submission"
fi

finish
