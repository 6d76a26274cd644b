#!/usr/bin/env bash
# scripts/test_faults.sh - faults, bad input and concurrent runs, through the real gapbeam
# executable (issue 12); each case checks the desired behaviour, and its name says what a case
# did before it was fixed ("was: ...").
#
# Usage:
#   scripts/test_faults.sh GAPBEAM_EXE     (scripts/test.sh calls it with the debug build)
#
# Every case runs in a fresh temporary directory (the working directory of the run), on a deck of
# inputs/ or test/decks/ (or a copy of one, edited) with command-line overrides that make it cheap
# (2 + 4 forcing periods, a Lyapunov exponent over 2 periods, no sweep progress lines) and put the
# output prefix in that directory. The run gets a time limit (GAPBEAM_FAULTS_TIMEOUT, default 20 s;
# some cases more or less) and an address-space limit of 1 GiB (`ulimit -v`), OMP_NUM_THREADS=1.
#
# Sections: negative nodes and list entries; overflow; over-long values; empty values; line ends;
# exit statuses (and GAPBEAM_BACKTRACE=1); fuzz findings; then files, locks, checkpoints, sweeps
# and merges:
#   full disk     `ulimit -f 100` (works for anyone: a write past the limit fails with EFBIG,
#                 gapbeam ignores SIGXFSZ) and, when run as root where `mount -t tmpfs` works, a
#                 200 KB tmpfs (ENOSPC): transient, HDF5, sweep (checkpoint kept and used) and
#                 merge; skipped with a NOTE line otherwise
#   output sets   a file in the way of the last table: the previous .h5 untouched; /run/files;
#                 the same for a continuation, and a continuation on a full disk (ulimit -f);
#                 an output prefix that names a directory refused
#   locks         5 sweeps and 6 transients started together on one prefix (one runs, the others
#                 exit 4, the files equal a single run's); a stale lock; another host's lock
#   checkpoints   a sweep stopped by --time-limit, its checkpoint corrupted (bit flip, NaN,
#                 duplicate, conflicting valid record, torn tail, old formats, damaged header,
#                 a middle record's mark or length, another deck's records spliced in, a forged
#                 'failed' record), then resumed: reported and recomputed (results equal an
#                 uninterrupted run) or refused
#   SIGTERM       a sweep stopped by SIGTERM: chunk finished, checkpoint kept, exit 3, resumed
#   lock statuses exit 4 only for a lock held by another run; a lock file that cannot be
#                 created or written, or whose name is too long, is exit 1 with the reason
#   options       --shard, --time-limit, --progress values read whole; merge --quiet OUT
#   shard costs   shards dealt by --shard-costs merge into the whole run's tables
#   sweeps        a failed first point; scripts/slurm_sweep.sh into a missing directory
#   merge         output equal to an input; an input given twice
#   studies       a diverged work-precision run is failed, never "reached"
#
# Checks:
#   clean error  exit status 1; stderr is exactly one line, starting `error: `, naming the deck
#                path as given, the group `&GROUP` and each expected word (variable names); no
#                `ERROR STOP`, `Backtrace`, `Fortran runtime`, `At line`; no file but the deck
#                (and copies of it) left in the case directory.
#   ok           exit status 0; PREFIX.h5 exists; nothing like a runtime error or warning on
#                stderr (`At line`, `Fortran runtime`, `ERROR STOP`, `Backtrace`).
#   (the other cases check what their name says)
# Prints `PASS  faults: <case>` or `FAIL  faults: <case> (<why>; stderr was: ...)` per case (and
# `NOTE  faults: ...` lines), then `test_faults.sh: N checks, M failed`; exit status 1 if any case
# failed. Needs python3 (stdlib) for the checkpoint cases.
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

# First 300 characters of stderr (of the case's run, or of the file $1) on one line.
stderr_line() {
   local s
   s=$(head -c 2000 "${1:-${dir}/run.stderr}")
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
expect_clean_error '&stops node=-1 is an error (was: runs with no stop)' stops node

new_case; run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" "$(out_override out)" \
   '&stops node=5, -1 /'
expect_clean_error '&stops node=5, -1 is an error (was: entry 2 dropped)' stops node

new_case; run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" "$(out_override out)" \
   '&masses node=-1, mass=1.0 /'
expect_clean_error '&masses node=-1, mass=1.0 is an error (was: the mass is dropped)' masses node

new_case; run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" "$(out_override out)" \
   '&springs node=-1, stiffness=1.0e3 /'
expect_clean_error '&springs node=-1 is an error (was: the spring is dropped)' springs node

new_case; run "${default_timeout}" "${inputs}/sweep_line_4mm.nml" "$(out_override out)" \
   "${sweep_cheap[@]}" '&sweep n_frequency=0, frequency_hz=9.5, 10.0, -1 /'
expect_clean_error 'sweep frequency_hz list ending in -1 is an error (was: -1 dropped)' \
   sweep frequency_hz

new_case; run "${default_timeout}" "${inputs}/sweep_grid_gap.nml" "$(out_override out)" \
   "${sweep_cheap[@]}" '&sweep n_frequency=2, n_amplitude=0, amplitude_pp=1.0e-3, 2.0e-3, -1 /'
expect_clean_error 'sweep amplitude_pp list ending in -1 is an error (was: -1 dropped)' \
   sweep amplitude_pp

# ---- overflow -----------------------------------------------------------------------------------
new_case; run "${default_timeout}" "${inputs}/sweep_grid_gap.nml" "$(out_override out)" \
   "${sweep_cheap[@]}" '&sweep n_frequency=65536 n_amplitude=65536 /'
expect_clean_error 'sweep 65536 x 65536 points is an error (was: 0 points, exit 0)' \
   sweep n_frequency

new_case; run "${default_timeout}" "${inputs}/sweep_grid_gap.nml" "$(out_override out)" \
   "${sweep_cheap[@]}" '&sweep n_frequency=50000 n_amplitude=50000 /'
expect_clean_error 'sweep 50000 x 50000 points is an error (was: a negative count)' \
   sweep n_frequency

new_case; run 10 "${inputs}/sweep_grid_gap.nml" "$(out_override out)" \
   "${sweep_cheap[@]}" '&sweep n_frequency=100000000 /'
expect_clean_error 'sweep n_frequency=100000000: an error within 10 s and 1 GiB (was: 2.3 GB allocated)' \
   sweep n_frequency

new_case; run "${default_timeout}" "${inputs}/moon_shaw_10p5hz.nml" "$(out_override out)" \
   '&solver transient_periods=2147483647, record_periods=100000000, steps_per_period=100000000, max_halvings=40 /'
expect_clean_error 'transient_periods + record_periods overflow is an error (was: the 2**62 tick check passes)' \
   solver transient_periods

new_case; run "${default_timeout}" "${inputs}/moon_shaw_10p5hz.nml" "$(out_override out)" \
   '&solver record_periods=2147483647 /'
expect_clean_error 'record_periods=2147483647 is refused before any allocation' \
   solver record_periods

new_case; run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" "$(out_override out)" \
   '&beam thickness=1.0e308 /'
expect_clean_error '&beam thickness=1e308 (EI overflows) is an error naming it (was: dsygv info=8)' \
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
report "&job output of ${#long} characters: used whole or refused (was: cut at 256, lands elsewhere)" \
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
report '&job title of 300 characters: used whole or refused (was: cut at 256)' "${why[@]}"

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
report 'override of 5000+ characters: read whole or refused with its length (was: End of file)' \
   "${why[@]}"

# ---- empty values -------------------------------------------------------------------------------
new_case; run "${default_timeout}" "${inputs}/moon_shaw_10p5hz.nml" "$(out_override out)" \
   "${cheap[@]}" '&forcing frequency_hz = , /'
expect_clean_error '&forcing frequency_hz = , is an error (was: the deck value is kept)' \
   forcing frequency_hz

new_case; d=$(copy_deck moon_shaw_modes.nml)
sed -i 's/n_elem = 4 /n_elem = , /' "${d}"
run "${default_timeout}" "${d}" "$(out_override out)"
expect_clean_error 'n_elem = , in the deck file is an error (was: the default 4 is used)' \
   beam n_elem

# ---- line ends ----------------------------------------------------------------------------------
new_case; d=$(copy_deck moon_shaw_modes.nml)
tr '\n' '\r' <"${inputs}/moon_shaw_modes.nml" >"${d}"
run "${default_timeout}" "${d}" "$(out_override out)"
expect_ok 'CR-only line ends run like LF (was: required group &job is missing)' "${dir}/out"

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
expect_ok 'a sweep into a missing directory (was: the checkpoint cannot be created)' \
   "${dir}/new/sub/out"

new_case; run "${default_timeout}" "${inputs}/model_size_10p5hz.nml" "$(out_override out)" \
   "${cheap[@]}" '&model_size elements=2, 3, modes=1 /'
why=()
grep -q '^model size: 2 meshes and 2 modal models' "${dir}/run.stdout" \
   || why+=("stdout: '$(grep '^model size' "${dir}/run.stdout")', want 2 meshes and 2 modal models")
mapfile -t more < <(ok_reasons "${dir}/out")
report '&model_size elements=2, 3, modes=1 runs that ladder (was: the default tail is kept)' \
   "${why[@]}" "${more[@]}"

new_case; run 10 "${inputs}/moon_shaw_10p5hz.nml" "$(out_override out)" "${cheap[@]}" \
   "&solver method='exact' /" '&forcing amplitude_pp=0 /'
expect_ok "method='exact' from rest without forcing ends within 10 s (was: hangs)" "${dir}/out"

new_case; run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" "$(out_override out)" \
   '&stops rule_f1_ratio=NaN /'
expect_clean_error '&stops rule_f1_ratio=NaN is an error naming it (was: rule_f1_hz(1) = 0 is blamed)' \
   stops rule_f1_ratio

# =================================================================================================
# Files, locks, checkpoints, sweeps and merges (issue 12 items 1-5, 8-11)
# =================================================================================================
small=${root}/test/decks/sweep_small.nml      # 8 points, about 1 s in the debug build
transient_cheap=('&solver transient_periods=2, record_periods=4 /' '&diagnostics lyapunov_periods=2 /')
transient_big=('&solver transient_periods=20, record_periods=20 /')   # tables of about 160 KB

# Python (stdlib) tool for checkpoint files: corrupt them in the ways a disk, a copy or a kill
# would, keeping or recomputing the checksum (the layout is in src/io/gapbeam_checkpoint.f90).
ckpt_tool() {
   python3 - "$@" <<'PY'
import struct, sys, zlib
path, mode = sys.argv[1], sys.argv[2]
b = bytearray(open(path, 'rb').read())
deck_hash, siglen = struct.unpack_from('<qq', b, 20)
head = 36 + siglen

def records(b):
    pos, recs = head, []
    while pos + 12 <= len(b):
        m1, p, m = struct.unpack_from('<iii', b, pos)
        end = pos + 12 + 8 * m + 12
        if m1 != 1296253778 or end > len(b):
            break
        recs.append((pos, p, m, end))
        pos = end
    return recs

def seal(rec, m):                              # the checksum of a record: over the deck too
    crc = zlib.crc32(bytes(rec[4:12 + 8 * m]), deck_hash)
    struct.pack_into('<q', rec, 12 + 8 * m, crc)

recs = records(b)
if not recs:
    sys.exit('no records in ' + path)
r0, p0, m0, e0 = recs[0]
x0 = r0 + 12                                   # payload of record 1: status, period, label, ...
if mode == 'count':
    print(len(recs))
elif mode == 'flip':                           # one bit of the period of record 1
    b[x0 + 8 + 6] ^= 0x10
elif mode == 'nan':                            # its Lyapunov exponent replaced by NaN
    struct.pack_into('<d', b, x0 + 24, float('nan'))
elif mode == 'dup':                            # record 1 once more, at the end
    b += b[r0:e0]
elif mode == 'conflict':                       # a well-formed record of point 1, other period
    rec = bytearray(b[r0:e0])
    struct.pack_into('<d', rec, 12 + 8, 7.0)
    seal(rec, m0)
    b += rec
elif mode == 'failed':                         # record 1 forged as a failed run, checksum right
    struct.pack_into('<d', b, x0, 1.0)
    rec = bytearray(b[r0:e0])
    seal(rec, m0)
    b[r0:e0] = rec
elif mode in ('midmark', 'midlen'):            # the begin mark or the length of record 2
    r1 = recs[1][0]
    if mode == 'midmark':
        b[r1] ^= 0x01
    else:
        struct.pack_into('<i', b, r1 + 8, recs[1][2] + 3)
elif mode == 'splice':                         # another deck's records after this header
    other = bytearray(open(sys.argv[3], 'rb').read())
    _, oslen = struct.unpack_from('<qq', other, 20)
    b = b[:head] + other[36 + oslen:]
elif mode == 'torn':                           # the last record cut in the middle
    r, _, _, e = recs[-1]
    b = b[:r + (e - r) // 2]
elif mode == 'headcut':                        # killed while creating it: 30 header bytes
    b = b[:30]
elif mode == 'v1':
    b[0:20] = b'GAPBEAM-CHECKPOINT-1'
elif mode == 'v4':
    b[0:20] = b'GAPBEAM-CHECKPOINT-4'
elif mode == 'v5':
    b[0:20] = b'GAPBEAM-CHECKPOINT-5'
elif mode == 'header':                         # a byte of the deck text in the header
    b[36 + siglen // 2] ^= 0x01
else:
    sys.exit('unknown mode ' + mode)
if mode != 'count':
    open(path, 'wb').write(bytes(b))
PY
}

# Files (not directories) under the case directory other than the run's stdout/stderr, the
# decks and the names given.
files_left() {
   (cd "${dir}" && find . -type f ! -name 'run.std*' ! -name '*.nml' "$@" | sort | tr '\n' ' ')
}

# ---- item 11: exit statuses and the backtrace switch ---------------------------------------------
new_case; GAPBEAM_BACKTRACE=1 run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" \
   "$(out_override out)" '&beam length=-1 /'
why=()
[[ ${status} -eq 1 ]] || why+=("exit status ${status}, want 1")
grep -q '^error: .*length' "${dir}/run.stderr" || why+=('no error line')
grep -q 'Backtrace\|ERROR STOP' "${dir}/run.stderr" || why+=('no backtrace with GAPBEAM_BACKTRACE=1')
report 'GAPBEAM_BACKTRACE=1: the error line, then ERROR STOP and a backtrace, exit 1' "${why[@]}"

new_case; run "${default_timeout}" "${inputs}/moon_shaw_10p5hz.nml" "$(out_override out)" \
   '&solver step_control="half_step", half_step_tolerance=1.0e-8, max_halvings=0, transient_periods=0, record_periods=2 /'
why=()
[[ ${status} -eq 1 ]] || why+=("exit status ${status}, want 1")
mapfile -t more < <(crash_reasons)
[[ -z $(files_left) ]] || why+=("files left: $(files_left)")
report 'a run failing after it took the lock: exit 1, no lock file or result left' "${why[@]}" \
   "${more[@]}"

# ---- item 1: a full disk (or the file size limit) is an error, never a truncated file ------------
# `ulimit -f` works for anyone: a write past the limit fails with EFBIG (gapbeam ignores
# SIGXFSZ), like a write to a full disk. gfortran reports neither: the sizes on disk tell.
new_case
# 250 KB: the .h5 (about 205 KB, with its units, long names, /parameters and /model) fits, the
# history table of 128 samples a period (about 320 KB) does not
(ulimit -f 250; run "${default_timeout}" "${inputs}/moon_shaw_10p5hz.nml" "$(out_override out)" \
   "${transient_big[@]}" '&output samples_per_period = 128 /'; \
   printf '%s' "${status}" >"${dir}/status")
status=$(<"${dir}/status"); rm -f "${dir}/status"
why=()
mapfile -t why < <(crash_reasons)
[[ ${status} -eq 1 ]] || why+=("exit status ${status}, want 1")
[[ $(grep -c '' "${dir}/run.stderr") -eq 1 ]] || why+=('stderr is not one line')
grep -q '^error: .*is incomplete: [0-9]* of [0-9]* bytes stored' "${dir}/run.stderr" \
   || why+=('the error does not say the file is incomplete')
[[ -z $(files_left) ]] || why+=("files left: $(files_left)")
report 'ulimit -f 250: a transient whose tables do not fit fails, no file left' "${why[@]}"

new_case
run "${default_timeout}" "${inputs}/moon_shaw_10p5hz.nml" "$(out_override out)" "${transient_cheap[@]}"
(cd "${dir}" && md5sum out.h5 out.history.dat out.poincare.dat >before.md5)
(ulimit -f 100; run "${default_timeout}" "${inputs}/moon_shaw_10p5hz.nml" "$(out_override out)" \
   "${transient_big[@]}"; printf '%s' "${status}" >"${dir}/status")
status=$(<"${dir}/status"); rm -f "${dir}/status"
why=()
[[ ${status} -eq 1 ]] || why+=("exit status ${status}, want 1")
(cd "${dir}" && md5sum -c --quiet before.md5 >/dev/null 2>&1) || why+=('the previous set changed')
left=$(files_left ! -name before.md5 ! -name out.h5 ! -name out.history.dat ! -name out.poincare.dat)
[[ -z ${left} ]] || why+=("other files left: ${left}")
report 'a failed write leaves the previous complete set untouched (.h5 and tables)' "${why[@]}"

# a real full disk: a 200 KB tmpfs, where the suite runs as root and may mount one
tmpfs_dir=''
if [[ $(id -u) -eq 0 ]]; then
   tmpfs_dir=$(mktemp -d "${top}/tmpfs-XXXXXX")
   if ! mount -t tmpfs -o size=200k tmpfs "${tmpfs_dir}" 2>/dev/null; then
      printf 'NOTE  faults: disk-full tests on a tmpfs skipped: mount -t tmpfs failed (a container without CAP_SYS_ADMIN?); the ulimit -f tests above cover the same code\n'
      tmpfs_dir=''
   fi
else
   printf 'NOTE  faults: disk-full tests on a tmpfs skipped: not root (they need mount -t tmpfs); the ulimit -f tests above cover the same code\n'
fi
if [[ -n ${tmpfs_dir} ]]; then
   trap 'umount "${tmpfs_dir}" 2>/dev/null; rm -rf "${top}"' EXIT
   fill() {   # fill KB: leave about KB kilobytes free on the tmpfs
      rm -f "${tmpfs_dir}"/*
      head -c $(( (200 - $1) * 1024 )) /dev/zero >"${tmpfs_dir}/filler"
   }

   new_case; fill 200
   run "${default_timeout}" "${inputs}/moon_shaw_10p5hz.nml" "&job output='${tmpfs_dir}/t' /" \
      "${transient_big[@]}"
   why=()
   mapfile -t why < <(crash_reasons)
   [[ ${status} -eq 1 ]] || why+=("exit status ${status}, want 1")
   [[ $(grep -c '' "${dir}/run.stderr") -eq 1 ]] || why+=('stderr is not one line')
   left=$(cd "${tmpfs_dir}" && ls -A | grep -v '^filler$' | tr '\n' ' ')
   [[ -z ${left} ]] || why+=("left on the full disk: ${left}")
   report 'full disk (200 KB tmpfs): a transient fails with one error line, nothing left' "${why[@]}"

   new_case; fill 8
   run "${default_timeout}" "${inputs}/moon_shaw_10p5hz.nml" "&job output='${tmpfs_dir}/t' /" \
      "${transient_cheap[@]}" '&output write_text=.false. /'
   why=()
   mapfile -t why < <(crash_reasons)
   [[ ${status} -eq 1 ]] || why+=("exit status ${status}, want 1")
   [[ $(grep -c '' "${dir}/run.stderr") -eq 1 ]] || why+=('stderr is not one line')
   grep -q 'gapbeam_hdf5_output' "${dir}/run.stderr" || why+=('not the HDF5 writer failing')
   report 'full disk while HDF5 writes: one error line, no crash at exit (was SIGSEGV)' "${why[@]}"

   new_case; fill 20
   run 60 "${small}" "&job output='${tmpfs_dir}/s' /"
   why=()
   mapfile -t why < <(crash_reasons)
   [[ ${status} -eq 1 ]] || why+=("first run: exit status ${status}, want 1")
   [[ -f ${tmpfs_dir}/s.checkpoint ]] || why+=('the checkpoint was not kept')
   [[ ! -e ${tmpfs_dir}/s.h5 ]] || why+=('s.h5 exists')
   rm -f "${tmpfs_dir}/filler"
   run 60 "${small}" "&job output='${tmpfs_dir}/s' /"
   [[ ${status} -eq 0 ]] || why+=("second run: exit status ${status}, want 0")
   grep -q ' 8 already in the checkpoint' "${dir}/run.stdout" \
      || why+=('the second run did not take the 8 points from the checkpoint')
   [[ -f ${tmpfs_dir}/s.h5 && ! -e ${tmpfs_dir}/s.checkpoint ]] || why+=('no s.h5, or a checkpoint left')
   report 'full disk at the end of a sweep: exit 1, checkpoint kept; with space, it finishes from it' \
      "${why[@]}"

   new_case
   rm -f "${tmpfs_dir}"/*
   for i in 1 2; do
      run 60 "${small}" --shard "${i}/2" "$(out_override s)"
   done
   fill 4
   status=0
   (cd "${dir}" && timeout 60 "${exe}" merge "${tmpfs_dir}/m.h5" s.shard_1_of_2.h5 s.shard_2_of_2.h5 \
      </dev/null >"${dir}/run.stdout" 2>"${dir}/run.stderr") || status=$?
   why=()
   mapfile -t why < <(crash_reasons)
   [[ ${status} -eq 1 ]] || why+=("exit status ${status}, want 1")
   [[ $(grep -c '' "${dir}/run.stderr") -eq 1 ]] || why+=('stderr is not one line')
   grep -q '^error: gapbeam merge: ' "${dir}/run.stderr" || why+=("no 'error: gapbeam merge:' line")
   left=$(cd "${tmpfs_dir}" && ls -A | grep -v '^filler$' | tr '\n' ' ')
   [[ -z ${left} ]] || why+=("left on the full disk: ${left}")
   report 'merge onto a full disk: one error line, exit 1, no crash (was SIGSEGV)' "${why[@]}"
   rm -f "${tmpfs_dir}"/*
fi

# ---- item 10: a run's files appear together or not at all ---------------------------------------
new_case
run "${default_timeout}" "${inputs}/moon_shaw_10p5hz.nml" "$(out_override out)" \
   "${transient_cheap[@]}" '&output write_text=.false. /'
(cd "${dir}" && md5sum out.h5 >before.md5)
mkdir "${dir}/out.poincare.dat"                  # in the way of the second run's last table
run "${default_timeout}" "${inputs}/moon_shaw_10p5hz.nml" "$(out_override out)" \
   "${transient_cheap[@]}"
why=()
mapfile -t why < <(crash_reasons)
[[ ${status} -eq 1 ]] || why+=("exit status ${status}, want 1")
(cd "${dir}" && md5sum -c --quiet before.md5 >/dev/null 2>&1) || why+=('out.h5 changed')
left=$(files_left ! -name before.md5 ! -name out.h5)
[[ -z ${left} ]] || why+=("other files: ${left}")
report 'a later file of the set fails: the new .h5 is not put beside the old files' "${why[@]}"

new_case
run "${default_timeout}" "${inputs}/moon_shaw_10p5hz.nml" "$(out_override out)" "${transient_cheap[@]}"
why=()
for f in out.h5 out.history.dat out.poincare.dat; do
   grep -aq "${f}" "${dir}/out.h5" || why+=("out.h5 does not list ${f}")
done
grep -aq 'run/files\|files' "${dir}/out.h5" || why+=('no /run/files')
report 'the .h5 lists its sibling files (/run/files)' "${why[@]}"

# ---- the continuation's files are one output set too ---------------------------------------------
cont=${root}/test/decks/sdof_continuation.nml
cont_cheap=('&continuation parameter_max = 3.6 /' '&output write_text = .true. /')
cont_files=(out.h5 out.branches.dat out.bifurcations.dat out.multipliers.dat out.curves.dat)
new_case
run "${default_timeout}" "${cont}" "$(out_override out)" "${cont_cheap[@]}" \
   '&output write_text = .false. /'
(cd "${dir}" && md5sum out.h5 >before.md5)
mkdir "${dir}/out.curves.dat"                    # in the way of the second run's last table
run "${default_timeout}" "${cont}" "$(out_override out)" "${cont_cheap[@]}"
why=()
mapfile -t why < <(crash_reasons)
[[ ${status} -eq 1 ]] || why+=("exit status ${status}, want 1")
[[ $(grep -c '' "${dir}/run.stderr") -eq 1 ]] || why+=('stderr is not one line')
(cd "${dir}" && md5sum -c --quiet before.md5 >/dev/null 2>&1) || why+=('out.h5 changed')
left=$(files_left ! -name before.md5 ! -name out.h5)
[[ -z ${left} ]] || why+=("other files: ${left}")
report 'continuation: a later file of the set fails: nothing new under final names, no .part left (was: PREFIX.h5 and tables put in place, exit 1)' "${why[@]}"

new_case
run "${default_timeout}" "${cont}" "$(out_override out)" "${cont_cheap[@]}"
why=()
mapfile -t why < <(ok_reasons "${dir}/out")
for f in "${cont_files[@]}"; do
   [[ -f ${dir}/${f} ]] || why+=("no ${f}")
   grep -aq "${f}" "${dir}/out.h5" || why+=("out.h5 does not list ${f}")
done
(cd "${dir}" && md5sum "${cont_files[@]}" >before.md5)
(ulimit -f 40; run "${default_timeout}" "${cont}" "$(out_override out)" "${cont_cheap[@]}" \
   '&continuation parameter_max = 6.0 /'; printf '%s' "${status}" >"${dir}/status")
status=$(<"${dir}/status"); rm -f "${dir}/status"
mapfile -t more < <(crash_reasons)
[[ ${status} -eq 1 ]] || why+=("second run (ulimit -f 40): exit status ${status}, want 1")
(cd "${dir}" && md5sum -c --quiet before.md5 >/dev/null 2>&1) || why+=('the previous set changed')
left=$(files_left ! -name before.md5 ! -name 'out.*.dat' ! -name out.h5)
[[ -z ${left} ]] || why+=("other files left: ${left}")
report 'continuation: its .h5 lists its four tables (/run/files); a full disk (ulimit -f 40) leaves the previous set untouched, no .part' "${why[@]}" "${more[@]}"

# ---- an output prefix that names a directory is refused -----------------------------------------
for prefix in 'results/x/' '.' '..' '/'; do
   new_case
   run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" "&job output='${prefix}' /"
   expect_clean_error "&job output='${prefix}' names a directory: refused, nothing made (was: hidden files such as results/x/.h5)" \
      job output 'names a directory'
done
new_case
run "${default_timeout}" "${small}" --shard 1/2 "$(out_override s)"
status=0
(cd "${dir}" && timeout 60 "${exe}" merge "${dir}/m/" s.shard_1_of_2.h5 </dev/null \
   >"${dir}/run.stdout" 2>"${dir}/run.stderr") || status=$?
why=()
mapfile -t why < <(crash_reasons)
[[ ${status} -eq 1 ]] || why+=("exit status ${status}, want 1")
grep -q "^error: gapbeam merge: .*names a directory" "${dir}/run.stderr" \
   || why+=('no one-line error naming the directory')
[[ ! -e ${dir}/m ]] || why+=('the directory m/ was made')
report 'merge into an output that names a directory (m/): refused' "${why[@]}"

# ---- item 3: one writer per output prefix -------------------------------------------------------
# N runs started together (a barrier file), on one prefix: one runs, the others exit 4 at once
# naming the holder (also when refused between the holder's flock and its writing its name into
# the lock file); the files are those of a single run; no lock file is left. A run that fails
# a check has its own stderr quoted (the report's 'stderr was' is the case's reference run's).
concurrent() {   # concurrent N NAME DECK ARG...: runs N copies in ${dir}/c<k>
   local n=$1 name=$2 k
   shift 2
   rm -f "${dir}/go"
   for ((k = 1; k <= n; k++)); do
      mkdir -p "${dir}/c${k}"
      ( while [[ ! -e ${dir}/go ]]; do sleep 0.005; done
        cd "${dir}" && timeout 120 "${exe}" "$@" </dev/null >"${dir}/c${k}/stdout" \
           2>"${dir}/c${k}/stderr"; printf '%s' "$?" >"${dir}/c${k}/status" ) &
   done
   sleep 0.2; : >"${dir}/go"; wait
   local ok=0 locked=0 other=0 s n_why
   why=()
   for ((k = 1; k <= n; k++)); do
      s=$(<"${dir}/c${k}/status")
      n_why=${#why[@]}
      if [[ ${s} -eq 0 ]]; then
         ok=$((ok + 1))
      elif [[ ${s} -eq 4 ]]; then
         locked=$((locked + 1))
         [[ $(grep -c '' "${dir}/c${k}/stderr") -eq 1 ]] || why+=("run ${k}: stderr not one line")
         grep -q '^error: .*is in use by another gapbeam run (pid [0-9]* on host ' \
            "${dir}/c${k}/stderr" || why+=("run ${k}: no 'in use by another gapbeam run' line")
      else
         other=$((other + 1)); why+=("run ${k}: exit status ${s}")
      fi
      [[ ${#why[@]} -eq ${n_why} ]] \
         || why+=("run ${k}'s stderr: $(stderr_line "${dir}/c${k}/stderr")")
   done
   printf 'NOTE  faults: %s: %d runs: %d ran, %d refused (lock)\n' "${name}" "${n}" "${ok}" "${locked}"
   [[ ${ok} -ge 1 ]] || why+=('no run succeeded')
   [[ ${locked} -ge 1 ]] || why+=('no run was refused: the runs did not overlap')
   [[ ! -e ${dir}/out.lock ]] || why+=('out.lock left')
}

new_case
run 60 "${small}" "$(out_override ref)"
concurrent 5 '5 sweeps on one prefix' "${small}" "$(out_override out)"
cmp -s "${dir}/ref.sweep.dat" "${dir}/out.sweep.dat" && cmp -s "${dir}/ref.bifurcation.dat" \
   "${dir}/out.bifurcation.dat" || why+=('the results differ from a single run')
report '5 simultaneous sweeps on one prefix: one runs, the others exit 4, results intact' "${why[@]}"

new_case
run "${default_timeout}" "${inputs}/moon_shaw_10p5hz.nml" "$(out_override ref)" "${transient_big[@]}"
concurrent 6 '6 transients on one prefix' "${inputs}/moon_shaw_10p5hz.nml" "$(out_override out)" \
   "${transient_big[@]}"
cmp -s "${dir}/ref.poincare.dat" "${dir}/out.poincare.dat" && cmp -s "${dir}/ref.history.dat" \
   "${dir}/out.history.dat" || why+=('the results differ from a single run')
report '6 simultaneous transients on one prefix: one runs, the others exit 4, results intact' \
   "${why[@]}"

new_case
sleep 0 & dead=$!; wait "${dead}"
printf 'gapbeam lock: pid %s host %s\n' "${dead}" "$(hostname)" >"${dir}/out.lock"
run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" "$(out_override out)"
why=()
mapfile -t why < <(crash_reasons)
[[ ${status} -eq 0 ]] || why+=("exit status ${status}, want 0")
grep -q "note: took over the stale lock .*out.lock' of pid ${dead} on host" "${dir}/run.stderr" \
   || why+=('no note about the stale lock')
[[ -f ${dir}/out.h5 && ! -e ${dir}/out.lock ]] || why+=('no out.h5, or out.lock left')
report 'a stale lock of a dead process on this host is taken over, with a note' "${why[@]}"

new_case
printf 'gapbeam lock: pid 4242 host some-other-host.example\n' >"${dir}/out.lock"
run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" "$(out_override out)"
why=()
mapfile -t why < <(crash_reasons)
[[ ${status} -eq 4 ]] || why+=("exit status ${status}, want 4")
grep -q 'names pid 4242 on host some-other-host.example' "${dir}/run.stderr" \
   || why+=('the error does not name the holder')
[[ ! -e ${dir}/out.h5 && -f ${dir}/out.lock ]] || why+=('out.h5 written, or the lock file removed')
report 'a lock file naming another host is refused (exit 4), not taken over' "${why[@]}"

# a run refused between the holder's flock and its line in the lock file (a fresh, empty file):
# the message names the holder once it has written its line (was: 'holder unknown', the cause
# of the rare unmatched line among 6 simultaneous runs); flock(1) plays the holder
new_case
flock -n "${dir}/out.lock" -c "sleep 1; printf 'gapbeam lock: pid %s host %s\\n' \"\$\$\" \
   \"$(hostname)\" >'${dir}/out.lock'; sleep 1" &
holder=$!
sleep 0.3
run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" "$(out_override out)"
wait "${holder}" || true
why=()
mapfile -t why < <(crash_reasons)
[[ ${status} -eq 4 ]] || why+=("exit status ${status}, want 4")
grep -q '^error: .*is in use by another gapbeam run (pid [0-9]* on host ' "${dir}/run.stderr" \
   || why+=('the error does not name the holder')
[[ ! -e ${dir}/out.h5 ]] || why+=('out.h5 written')
report 'a run refused while the holder has not yet named itself in the new lock file names it' \
   "${why[@]}"

# ---- item 5: checkpoints: a record is trusted only with its checksum -----------------------------
# a sweep stopped by its time limit after a chunk of 4 of its 8 points, its checkpoint corrupted,
# then run again: the results must equal an uninterrupted run's
checkpoint_case() {   # checkpoint_case MODE WANT_STATUS STDERR_PATTERN NAME [OTHER_OVERRIDE]
   local mode=$1 want=$2 pattern=$3 name=$4 other=${5:-}
   new_case
   run 60 "${small}" "$(out_override ref)"
   if [[ -n ${other} ]]; then       # another deck's checkpoint, for its records
      run 60 "${small}" "$(out_override other)" '&sweep chunk=4 /' "${other}" --time-limit 0.000001
   fi
   run 60 "${small}" "$(out_override out)" '&sweep chunk=4 /' --time-limit 0.000001
   why=()
   [[ ${status} -eq 3 && -f ${dir}/out.checkpoint ]] || why+=("interrupted run: exit status ${status}, want 3 and a checkpoint")
   ckpt_tool "${dir}/out.checkpoint" "${mode}" "${dir}/other.checkpoint" || why+=("ckpt_tool ${mode} failed")
   run 60 "${small}" "$(out_override out)" '&sweep chunk=4 /'
   mapfile -t more < <(crash_reasons)
   why+=("${more[@]}")
   [[ ${status} -eq ${want} ]] || why+=("exit status ${status}, want ${want}")
   if [[ -n ${pattern} ]]; then
      grep -q -- "${pattern}" "${dir}/run.stderr" || why+=("stderr lacks '${pattern}'")
   fi
   if [[ ${want} -eq 0 ]]; then
      cmp -s "${dir}/ref.sweep.dat" "${dir}/out.sweep.dat" && cmp -s "${dir}/ref.bifurcation.dat" \
         "${dir}/out.bifurcation.dat" || why+=('the results differ from an uninterrupted run')
      grep -q -- 'full disk' "${dir}/run.stderr" && why+=("'full disk' on stderr")
   else
      [[ -f ${dir}/out.checkpoint && ! -e ${dir}/out.h5 ]] || why+=('checkpoint removed, or out.h5 written')
   fi
   report "${name}" "${why[@]}"
}
checkpoint_case flip 0 'fails its checksum' 'a flipped bit in a checkpoint record: reported, the point recomputed'
checkpoint_case nan 0 'fails its checksum' 'a NaN written into a checkpoint record: reported, the point recomputed'
checkpoint_case dup 0 '' 'a duplicated checkpoint record: harmless, results unchanged'
checkpoint_case conflict 0 'two different records' 'two valid records of one point that differ: neither trusted'
checkpoint_case torn 0 'not a whole record' 'a torn last record (killed while writing): dropped, recomputed'
checkpoint_case headcut 0 'cut short in its header' \
   'a checkpoint cut short in its header (killed while creating it): started afresh (was: refused)'
checkpoint_case v1 1 'older gapbeam' 'a checkpoint of the old format (no checksums): refused'
checkpoint_case v4 1 'do not cover the deck' 'a checkpoint of format 4 (checksums without the deck): refused'
checkpoint_case v5 1 'starts and the rerun periods' 'a checkpoint of format 5 (no exponent starts): refused'
checkpoint_case header 1 'damaged header' 'a damaged deck text in the checkpoint header: refused'
checkpoint_case midmark 0 'a damaged mark or length' \
   "a middle record's damaged begin mark: skipped, the rest read, the point recomputed (was: 'a full disk?')"
checkpoint_case midlen 0 'a damaged mark or length' \
   "a middle record's damaged length: skipped, the rest read, the point recomputed (was: 'a full disk?')"
checkpoint_case splice 0 'another deck or shard' \
   "another deck's records spliced after this header: refused by their checksums (was: loaded)" \
   '&sweep amplitude_pp = 2.5e-3, 4.5e-3 /'
checkpoint_case failed 0 'records a failed run' \
   "a forged 'failed' record with a right checksum: recomputed (was: never recomputed, exit 5)"

# the records after a damaged middle record are read, not recomputed (3 of the 4 points come
# from the checkpoint), and the file is rewritten clean: the run after reports nothing
new_case
run 60 "${small}" "$(out_override ref)"
run 60 "${small}" "$(out_override out)" '&sweep chunk=4 /' --time-limit 0.000001
ckpt_tool "${dir}/out.checkpoint" midmark
run 60 "${small}" "$(out_override out)" '&sweep chunk=4 /' --time-limit 0.000001
why=()
mapfile -t why < <(crash_reasons)
[[ ${status} -eq 3 ]] || why+=("second run: exit status ${status}, want 3")
grep -q ' 3 already in the checkpoint' "${dir}/run.stdout" || why+=('not 3 points from the checkpoint')
grep -q 'a damaged mark or length' "${dir}/run.stderr" || why+=('the damage was not reported')
run 60 "${small}" "$(out_override out)" '&sweep chunk=4 /'
[[ ${status} -eq 0 ]] || why+=("third run: exit status ${status}, want 0")
grep -q ' 7 already in the checkpoint' "${dir}/run.stdout" || why+=('third run: not 7 points from the checkpoint')
grep -q 'checkpoint' "${dir}/run.stderr" && why+=('third run: the checkpoint was reported again (not rewritten clean)')
cmp -s "${dir}/ref.sweep.dat" "${dir}/out.sweep.dat" || why+=('the results differ from an uninterrupted run')
report 'a damaged middle record: the records after it are used (3 of 4), the file rewritten clean, results unchanged' \
   "${why[@]}"

# ---- SIGTERM (a batch job's time limit, preemption, scancel) stops a sweep like its time limit --
new_case
slow=('&sweep chunk=1 /' '&solver steps_per_period=2048 /')
run 60 "${small}" "$(out_override ref)" "${slow[@]}"
status=0
(cd "${dir}" && exec timeout --kill-after=5 60 "${exe}" "${small}" "$(out_override out)" "${slow[@]}" \
   </dev/null >"${dir}/run.stdout" 2>"${dir}/run.stderr") &
pid=$!
for _ in $(seq 1 600); do      # until the first point is in the checkpoint (or the run ended)
   size=$(stat -c %s "${dir}/out.checkpoint" 2>/dev/null || echo 0)
   ((size > 2000)) && break
   kill -0 "${pid}" 2>/dev/null || break
   sleep 0.05
done
pkill -TERM -P "${pid}" 2>/dev/null || kill -TERM "${pid}" 2>/dev/null
wait "${pid}" || status=$?
why=()
mapfile -t why < <(crash_reasons)
[[ ${status} -eq 3 ]] || why+=("exit status ${status}, want 3")
grep -q 'stopped by SIGTERM after' "${dir}/run.stdout" || why+=("no 'stopped by SIGTERM' line")
[[ -f ${dir}/out.checkpoint && ! -e ${dir}/out.lock && ! -e ${dir}/out.h5 ]] \
   || why+=('no checkpoint kept, or the lock or out.h5 left')
run 60 "${small}" "$(out_override out)" "${slow[@]}"
[[ ${status} -eq 0 ]] || why+=("resumed run: exit status ${status}, want 0")
grep -q ' [1-8] already in the checkpoint' "${dir}/run.stdout" || why+=('the resumed run loaded no point')
cmp -s "${dir}/ref.sweep.dat" "${dir}/out.sweep.dat" || why+=('the results differ from an uninterrupted run')
report 'SIGTERM: the chunk finished, checkpoint kept, exit 3, lock released; resumed: same results (was: killed)' \
   "${why[@]}"

# ---- the lock: exit status 4 only when another run holds it --------------------------------------
new_case
mkdir "${dir}/out.lock"
run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" "$(out_override out)"
why=()
mapfile -t why < <(crash_reasons)
[[ ${status} -eq 1 ]] || why+=("exit status ${status}, want 1 (4 says another run holds the lock)")
grep -q "cannot create the lock file .*: Is a directory (errno 21)" "${dir}/run.stderr" \
   || why+=("the error does not give the system's reason in words")
report 'a lock file that cannot be created: exit 1 with the reason in words (was: exit 4, bare errno)' \
   "${why[@]}"

new_case
status=0      # the limit for gapbeam alone; its stderr through a pipe, which the limit spares
(cd "${dir}" && ulimit -f 0 && exec timeout 20 "${exe}" "${inputs}/moon_shaw_modes.nml" \
   "$(out_override out)" </dev/null 2>&1 >/dev/null) | cat >"${dir}/run.stderr"
status=${PIPESTATUS[0]}
why=()
mapfile -t why < <(crash_reasons)
[[ ${status} -eq 1 ]] || why+=("exit status ${status}, want 1")
grep -q "cannot write the lock file .*: File too large (errno 27)" "${dir}/run.stderr" \
   || why+=("the error does not give the system's reason in words")
[[ ! -e ${dir}/out.h5 ]] || why+=('out.h5 written')
report 'a lock file that cannot be written (ulimit -f 0, as a full disk): exit 1, reason in words (was: exit 4)' \
   "${why[@]}"

new_case
long=$(printf 'x%.0s' $(seq 1 252))
run "${default_timeout}" "${inputs}/moon_shaw_modes.nml" "&job output='${long}' /"   # in ${dir}
why=()
mapfile -t why < <(crash_reasons)
[[ ${status} -eq 1 ]] || why+=("exit status ${status}, want 1")
grep -qi "file name too long" "${dir}/run.stderr" || why+=("no 'file name too long'")
report 'an output name too long for the file system: exit 1 at the start, reason in words (was: exit 4)' \
   "${why[@]}"

# ---- options are parsed strictly; merge takes its options anywhere --------------------------------
for opt in '--shard 1//4' '--shard 1/4/2' '--shard 1/4x' '--time-limit 5 junk' '--time-limit=5junk' \
           '--progress 1e999'; do
   new_case
   run "${default_timeout}" "${small}" "$(out_override out)" "${opt%% *}" "${opt#* }"
   [[ ${opt} == *=* ]] && run "${default_timeout}" "${small}" "$(out_override out)" "${opt}"
   why=()
   mapfile -t why < <(crash_reasons)
   [[ ${status} -eq 1 ]] || why+=("exit status ${status}, want 1")
   grep -q "^error: .*'${opt#*[ =]}'" "${dir}/run.stderr" || why+=('the error does not quote the value')
   [[ -z $(files_left) ]] || why+=("files left: $(files_left)")
   report "option ${opt}: refused, the whole value must be read (was: taken in part)" "${why[@]}"
done
new_case
for i in 1 2; do run 60 "${small}" --shard "${i}/2" "$(out_override s)"; done
status=0
(cd "${dir}" && timeout 60 "${exe}" merge --quiet m.h5 s.shard_1_of_2.h5 s.shard_2_of_2.h5 \
   </dev/null >"${dir}/run.stdout" 2>"${dir}/run.stderr") || status=$?
why=()
mapfile -t why < <(crash_reasons)
[[ ${status} -eq 0 ]] || why+=("exit status ${status}, want 0")
[[ -f ${dir}/m.h5 && ! -e ${dir}/--quiet.h5 ]] || why+=('no m.h5, or --quiet.h5 written')
report 'merge --quiet OUT ...: --quiet is an option, OUT the output (was: --quiet taken as OUT)' "${why[@]}"

# ---- shards dealt by cost (--shard-costs): same merged result, another deal -----------------------
new_case
run 60 "${small}" "$(out_override ref)"
for i in 1 2 3; do
   run 60 "${small}" --shard "${i}/3" --shard-costs "${dir}/ref.h5" "$(out_override s)"
   [[ ${status} -eq 0 ]] || break
done
why=()
mapfile -t why < <(crash_reasons)
[[ ${status} -eq 0 ]] || why+=("a shard: exit status ${status}, want 0")
grep -q '^shards: dealt by the costs in ' "${dir}/run.stdout" || why+=("no 'shards: dealt by' line")
status=0
(cd "${dir}" && timeout 60 "${exe}" merge m.h5 s.shard_1_of_3.h5 s.shard_2_of_3.h5 s.shard_3_of_3.h5 \
   </dev/null >"${dir}/merge.stdout" 2>"${dir}/run.stderr") || status=$?
[[ ${status} -eq 0 ]] || why+=("merge: exit status ${status}, want 0")
cmp -s "${dir}/ref.sweep.dat" "${dir}/m.sweep.dat" && cmp -s "${dir}/ref.bifurcation.dat" \
   "${dir}/m.bifurcation.dat" || why+=('the merged tables differ from the whole run')
run 60 "${small}" --shard 1/3 --shard-costs "${dir}/s.shard_1_of_3.h5" "$(out_override t)"
[[ ${status} -eq 1 ]] && grep -q 'give the whole or merged file' "${dir}/run.stderr" \
   || why+=("a shard file as the costs: exit status ${status}, want 1 and an error")
report '--shard-costs: shards dealt by cost merge into the whole run (tables byte for byte); a shard file refused' \
   "${why[@]}"

# ---- item 2: a failed first sweep point ----------------------------------------------------------
new_case
for k in 1 2; do
   run "${default_timeout}" "${inputs}/sweep_grid_gap.nml" "$(out_override out)" "${sweep_cheap[@]}" \
      '&sweep n_frequency=0 n_amplitude=0 frequency_hz=9.0,10.0 amplitude_pp=1e300,2e-3 /'
   # failed points: every file written, then exit status 5 (issue 11: never silent)
   mapfile -t why < <(crash_reasons)
   [[ ${status} -eq 5 ]] || why+=("exit status ${status}, want 5 (points failed)")
   [[ -f ${dir}/out.h5 ]] || why+=('no out.h5')
   grep -q 'failed: 2$' "${dir}/run.stdout" || why+=("run ${k}: the summary does not count 2 failed points")
   [[ ${#why[@]} -eq 0 ]] || break
done
report 'a sweep whose first point fails writes its file (was SIGSEGV), also when run again' "${why[@]}"

# ---- item 4: slurm_sweep.sh into a missing directory ----------------------------------------------
new_case
status=0
(cd "${dir}" && GAPBEAM=${exe} timeout 60 bash "${root}/scripts/slurm_sweep.sh" "${small}" \
   "&job output='${dir}/new/dir/s' /" </dev/null >"${dir}/run.stdout" 2>"${dir}/run.stderr") \
   || status=$?
why=()
mapfile -t why < <(crash_reasons)
[[ ${status} -eq 0 ]] || why+=("exit status ${status}, want 0")
[[ -f ${dir}/new/dir/s.h5 ]] || why+=('no new/dir/s.h5')
report 'scripts/slurm_sweep.sh writes into a directory that does not exist yet' "${why[@]}"

# ---- item 9: merge refuses to overwrite an input, and an input given twice -----------------------
new_case
for i in 1 2; do run 60 "${small}" --shard "${i}/2" "$(out_override s)"; done
(cd "${dir}" && md5sum s.shard_1_of_2.h5 s.shard_2_of_2.h5 >before.md5)
status=0
(cd "${dir}" && timeout 60 "${exe}" merge s.shard_1_of_2.h5 s.shard_1_of_2.h5 s.shard_2_of_2.h5 \
   </dev/null >"${dir}/run.stdout" 2>"${dir}/run.stderr") || status=$?
why=()
mapfile -t why < <(crash_reasons)
[[ ${status} -eq 1 ]] || why+=("exit status ${status}, want 1")
grep -q 'would be overwritten' "${dir}/run.stderr" || why+=('no message about the output')
(cd "${dir}" && md5sum -c --quiet before.md5 >/dev/null 2>&1) || why+=('a shard file changed')
report 'merge OUT equal to an input: refused, the input unchanged (was overwritten, exit 0)' "${why[@]}"
status=0
(cd "${dir}" && timeout 60 "${exe}" merge m.h5 s.shard_1_of_2.h5 ./s.shard_1_of_2.h5 \
   s.shard_2_of_2.h5 </dev/null >"${dir}/run.stdout" 2>"${dir}/run.stderr") || status=$?
why=()
mapfile -t why < <(crash_reasons)
[[ ${status} -eq 1 ]] || why+=("exit status ${status}, want 1")
grep -q 'given twice' "${dir}/run.stderr" || why+=("no 'given twice'")
[[ ! -e ${dir}/m.h5 ]] || why+=('m.h5 written')
report 'merge with one input given twice (another spelling): refused' "${why[@]}"

# ---- item 8: a diverged run is never reported as reaching an accuracy ---------------------------
new_case
run 60 "${inputs}/work_precision_15el.nml" "$(out_override out)" \
   "&study series='newmark_half_step', 'central_difference', 'exact', levels=2, periods=2 /"
mapfile -t why < <(ok_reasons "${dir}/out")
line=$(grep 'central_difference' "${dir}/out.work_precision.txt" 2>/dev/null || true)
[[ ${line} == *failed*failed* || ${line} == *'not reached'*'not reached'* ]] \
   || why+=("central_difference reported as reaching: '${line}'")
if grep -v '^#' "${dir}/out.wp_central_difference.dat" 2>/dev/null | grep -qi 'nan\|inf'; then
   why+=('a NaN or Inf row in out.wp_central_difference.dat')
fi
report 'work-precision: diverged central difference (NaN error) is failed, not a result' "${why[@]}"

printf 'test_faults.sh: %d checks, %d failed\n' "${n_checks}" "${n_failed}"
[[ ${n_failed} -eq 0 ]]
