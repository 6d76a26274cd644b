#!/usr/bin/env bash
# scripts/test_cli.sh - end-to-end tests of bad input through the real gapbeam executable.
#
# Usage:
#   scripts/test_cli.sh GAPBEAM_EXE
#   (scripts/test.sh calls it with the debug-built executable)
#
# Each case writes a deck (the valid base deck below with one change) into a fresh temporary
# directory, runs `GAPBEAM_EXE DECK [OVERRIDE ...]` there, and checks:
#   bad cases:  non-zero exit status, not a crash (signal, time-out, `Fortran runtime error`);
#               stderr names the deck path exactly as given, and contains each expected
#               substring (case-sensitive; matched after the deck path and the case directory are
#               removed from stderr, so that a digit in a temporary name cannot match);
#               no <dir>/out.h5 (nor out.h5.part) was written.
#   good cases: exit status 0, <dir>/out.h5 exists and no *.part file remains.
# Prints `PASS  cli: <case>` or `FAIL  cli: <case> (<why>; stderr was: ...)` per case, then
# `test_cli.sh: N checks, M failed`; exit status 1 if any case failed.
#
# Add a case with one line at the end of this file:
#   bad_case  "NAME" [EDIT ...] -- EXPECTED_SUBSTRING ...
#   good_case "NAME" [EDIT ...]
# where EDIT is one of
#   -r OLD NEW   replace the first OLD in the deck by NEW (literal text, no patterns)
#   -g GROUP     delete the namelist group &GROUP (from its line to the line ending in '/')
#   -a TEXT      append TEXT as a new line
#   -o ARG       pass ARG after the deck on the command line (an override)
#   -m           run on a deck path that does not exist (nothing is written)
#
# Environment: GAPBEAM_CLI_TIMEOUT  seconds allowed per run (default 120).
set -euo pipefail

if [[ $# -ne 1 || ${1:-} == -h || ${1:-} == --help ]]; then
   printf 'usage: %s GAPBEAM_EXE\n' "$0" >&2
   exit 2
fi
exe=$1
if [[ ! -f ${exe} || ! -x ${exe} ]]; then
   printf "FAIL  cli: GAPBEAM_EXE '%s' is not an executable file\n" "${exe}"
   printf 'test_cli.sh: 1 checks, 1 failed\n'
   exit 1
fi
[[ ${exe} == /* ]] || exe=${PWD}/${exe}

top=$(mktemp -d "${TMPDIR:-/tmp}/gapbeam-cli-XXXXXX")
trap 'rm -rf "${top}"' EXIT
case_timeout=${GAPBEAM_CLI_TIMEOUT:-120}
runner=()
if command -v timeout >/dev/null 2>&1; then
   runner=(timeout --kill-after=10 "${case_timeout}")
fi

# The valid base deck; @DIR@ becomes the case's temporary directory.
base_deck="! test deck
&job analysis='modes', title='cli test', output='@DIR@/out' /
&beam length=0.2, n_elem=4, youngs_modulus=200.0e9, density=7850.0,
      width=0.01, thickness=0.00026, mass_matrix='lumped', rotary_inertia='half_element' /
&root condition='spring', k_theta=0.0912 /
&springs node=5, dof='w', stiffness=1.0e3 /"

n_checks=0
n_failed=0

# Print TEXT with every OLD replaced by NEW, all literal.
replace_all() {
   local text=$1 old=$2 new=$3 out=""
   [[ -n ${old} ]] || { printf '%s' "${text}"; return 0; }
   while [[ ${text} == *"${old}"* ]]; do
      out+=${text%%"${old}"*}${new}
      text=${text#*"${old}"}
   done
   printf '%s' "${out}${text}"
}

# Print TEXT with the first OLD replaced by NEW (literal); false if OLD is not in TEXT.
replace_first() {
   local text=$1 old=$2 new=$3
   [[ ${text} == *"${old}"* ]] || return 1
   printf '%s' "${text%%"${old}"*}${new}${text#*"${old}"}"
}

# Print TEXT without namelist group &GROUP; false if there is no such group.
drop_group() {
   local text=$1 group=$2 line trimmed out="" skipping=0 found=0
   while IFS= read -r line; do
      trimmed=${line#"${line%%[![:space:]]*}"}
      if [[ ${skipping} -eq 0 && ( ${trimmed} == "&${group}" \
            || ${trimmed} == "&${group}"[[:space:]]* ) ]]; then
         skipping=1
         found=1
      fi
      if [[ ${skipping} -eq 1 ]]; then
         if [[ ${line} =~ /[[:space:]]*$ ]]; then skipping=0; fi
         continue
      fi
      out+=${line}$'\n'
   done <<<"${text}"
   [[ ${found} -eq 1 ]] || return 1
   printf '%s' "${out}"
}

# Print the first 400 characters of file $1 on one line (line breaks shown as ' | ').
one_line() {
   local s
   s=$(<"$1")
   s=${s//$'\n'/ | }
   if [[ -z ${s} ]]; then
      printf '(empty)'
   elif [[ ${#s} -gt 400 ]]; then
      printf '%s ...' "${s:0:400}"
   else
      printf '%s' "${s}"
   fi
}

# Record one case: report NAME DIR [WHY ...]; no WHY means it passed. DIR holds run.stderr.
report() {
   local name=$1 dir=$2 why
   shift 2
   n_checks=$((n_checks + 1))
   if [[ $# -eq 0 ]]; then
      printf 'PASS  cli: %s\n' "${name}"
      return 0
   fi
   n_failed=$((n_failed + 1))
   why=$(printf '%s; ' "$@")
   printf 'FAIL  cli: %s (%sstderr was: %s)\n' "${name}" "${why}" "$(one_line "${dir}/run.stderr")"
}

# run_case KIND NAME [EDIT ...] [-- EXPECTED ...]: build the deck, run, check, report.
run_case() {
   local kind=$1 name=$2 dir deck text status=0 missing=0 s stripped e
   local -a args=() expect=() why=()
   shift 2
   dir=$(mktemp -d "${top}/case-XXXXXX")
   : >"${dir}/run.stderr"
   text=$(replace_all "${base_deck}" '@DIR@' "${dir}")
   while [[ $# -gt 0 && $1 != -- ]]; do
      case $1 in
         -r) if ! text=$(replace_first "${text}" "$2" "$3"); then
                why+=("case definition: '$2' is not in the base deck")
             fi
             shift 3 ;;
         -g) if ! text=$(drop_group "${text}" "$2"); then
                why+=("case definition: no group &$2 in the base deck")
             fi
             shift 2 ;;
         -a) text+=$'\n'$2; shift 2 ;;
         -o) args+=("$2"); shift 2 ;;
         -m) missing=1; shift ;;
         *) why+=("case definition: unknown edit '$1'"); shift ;;
      esac
   done
   if [[ $# -gt 0 ]]; then shift; fi
   expect=("$@")
   if [[ ${#why[@]} -gt 0 ]]; then
      report "${name}" "${dir}" "${why[@]}"
      return 0
   fi

   if [[ ${missing} -eq 1 ]]; then
      deck=${dir}/absent.nml
   else
      deck=${dir}/deck.nml
      printf '%s\n' "${text}" >"${deck}"
   fi
   (cd "${dir}" && "${runner[@]}" "${exe}" "${deck}" "${args[@]}" \
      </dev/null >"${dir}/run.stdout" 2>"${dir}/run.stderr") || status=$?
   s=$(<"${dir}/run.stderr")

   if [[ ${kind} == good ]]; then
      [[ ${status} -eq 0 ]] || why+=("exit status ${status}, want 0")
      [[ -f ${dir}/out.h5 ]] || why+=("no out.h5 written")
      if compgen -G "${dir}/*.part" >/dev/null; then why+=("a .part file remains"); fi
      report "${name}" "${dir}" "${why[@]}"
      return 0
   fi

   if [[ ${status} -eq 0 ]]; then
      why+=("exit status 0, want non-zero")
   elif [[ ${status} -eq 124 || ${status} -eq 137 ]]; then
      why+=("timed out after ${case_timeout} s (status ${status})")
   elif [[ ${status} -gt 128 ]]; then
      why+=("crashed: status ${status} (signal $((status - 128)))")
   fi
   if [[ ${s} == *"Fortran runtime error"* ]]; then
      why+=("an unhandled Fortran runtime error, not a clean message")
   fi
   [[ ${s} == *"${deck}"* ]] || why+=("stderr lacks the deck path '${deck}'")
   stripped=$(replace_all "${s}" "${deck}" '')
   stripped=$(replace_all "${stripped}" "${dir}" '')
   for e in "${expect[@]}"; do
      [[ ${stripped} == *"${e}"* ]] || why+=("stderr lacks '${e}'")
   done
   [[ ! -e ${dir}/out.h5 ]] || why+=("out.h5 was written")
   [[ ! -e ${dir}/out.h5.part ]] || why+=("out.h5.part was left")
   report "${name}" "${dir}" "${why[@]}"
}

bad_case() { run_case bad "$@"; }
good_case() { run_case good "$@"; }

printf 'test_cli.sh: %s\n' "${exe}"

# ---- cases ------------------------------------------------------------------------------------
good_case "base deck runs and writes out.h5"
good_case "valid override accepted" -o '&beam n_elem=8 /'

bad_case "misspelled variable lenght"     -r 'length=0.2' 'lenght=0.2'          -- '&beam' 'lenght'
bad_case "misspelled group &bem"          -r '&beam ' '&bem '                   -- '&bem'
bad_case "missing required group &beam"   -g beam                               -- '&beam' 'missing'
bad_case "wrong type n_elem='four'"       -r 'n_elem=4' "n_elem='four'"         -- '&beam' 'n_elem'
bad_case "wrong type length=abc"          -r 'length=0.2' 'length=abc'          -- '&beam' 'length'
bad_case "negative length"                -r 'length=0.2' 'length=-0.2'         -- '&beam' 'length' '-0.2'
bad_case "zero thickness"                 -r 'thickness=0.00026' 'thickness=0.0' -- '&beam' 'thickness'
bad_case "negative youngs_modulus"        -r 'youngs_modulus=200.0e9' 'youngs_modulus=-200.0e9' \
                                                                                -- '&beam' 'youngs_modulus'
bad_case "zero elements n_elem=0"         -r 'n_elem=4' 'n_elem=0'              -- '&beam' 'n_elem'
bad_case "negative spring stiffness"      -r 'stiffness=1.0e3' 'stiffness=-1.0e3' -- '&springs' 'stiffness'
bad_case "spring node 9 outside the mesh" -r 'node=5' 'node=9'                  -- '&springs' 'node' '9'
bad_case "unknown mass_matrix 'lumpy'"    -r "mass_matrix='lumped'" "mass_matrix='lumpy'" \
                                                                -- '&beam' 'mass_matrix' 'lumpy' 'consistent'
bad_case "unknown root condition 'hinged'" -r "condition='spring'" "condition='hinged'" \
                                                                                -- '&root' 'condition' 'hinged'
bad_case "unknown analysis 'modez'"       -r "analysis='modes'" "analysis='modez'" -- '&job' 'analysis' 'modez'
bad_case "unknown dof word 'x'"           -r "dof='w'" "dof='x'"                -- '&springs' 'dof'
bad_case "missing deck file"              -m                                    -- 'deck'
bad_case "bad override &beam n_elem=-3"   -o '&beam n_elem=-3 /'                -- '&beam' 'n_elem' '-3'
bad_case "override of unknown group"      -o '&nosuch x=1 /'                    -- '&nosuch'
bad_case "negative point mass"            -a '&masses node=5, mass=-1.0 /'      -- '&masses' 'mass' '-1'
bad_case "zero root spring k_theta=0.0"   -r 'k_theta=0.0912' 'k_theta=0.0'     -- '&root' 'k_theta'

# numerical failures and the sweep's command line
bad_case "step below the minimum (transient)" -r "analysis='modes'" "analysis='transient'" \
   -a '&forcing frequency_hz=10.5, amplitude_pp=3.7e-3 /' \
   -a '&solver step_control="half_step", half_step_tolerance=1.0e-8, max_halvings=0, transient_periods=0, record_periods=2 /' \
   -- 'step below the minimum' 'dt' 't ='
bad_case "bad --shard value"                  -o '--shard' -o '4/3'                  -- '--shard' '4/3'
bad_case "--shard on a modes deck"            -o '--shard' -o '1/2'                  -- 'sweep'
bad_case "--shard 1//4 (was: the whole sweep)" -o '--shard' -o '1//4'                -- '--shard' "'1//4'"
bad_case "--shard 1/4/2 (was: run as 1/4)"    -o '--shard' -o '1/4/2'                -- '--shard' "'1/4/2'"
bad_case "--time-limit '5 junk' (was: 5 s)"   -o '--time-limit' -o '5 junk'          -- '--time-limit' "'5 junk'"
bad_case "--shard-costs on a modes deck"      -o '--shard-costs=x.h5'                -- '--shard-costs' 'sweep'
bad_case "sweep without &sweep"               -r "analysis='modes'" "analysis='sweep'" \
   -a '&forcing frequency_hz=10.5, amplitude_pp=3.7e-3 /'                          -- '&sweep' 'missing'
bad_case "sweep axis list and range both"     -r "analysis='modes'" "analysis='sweep'" \
   -a '&forcing frequency_hz=10.5, amplitude_pp=3.7e-3 /' \
   -a '&sweep frequency_hz=9.0, 10.0, n_frequency=4, frequency_start_hz=8.0, frequency_end_hz=9.0 /' \
   -- '&sweep' 'frequency_hz' 'n_frequency'

printf 'test_cli.sh: %d checks, %d failed\n' "${n_checks}" "${n_failed}"
[[ ${n_failed} -eq 0 ]]
