#!/usr/bin/env bash
# scripts/setup.sh - install what gapbeam needs to build, test and plot, where it is missing.
#
# Usage:
#   scripts/setup.sh           execute it: installs what is missing
#   source scripts/setup.sh    source it (run.sh and test.sh do): same, and also exports PATH
#                              so that a pip-installed `fpm` is found
#   scripts/setup.sh --slurm   also what scripts/test_slurm.sh needs (below); only that test asks
#
# Checks, and installs only what is missing:
#   gfortran                       apt: gfortran
#   LAPACK and BLAS (-llapack -lblas)  apt: liblapack-dev libopenblas-dev
#   HDF5 with its Fortran API      apt: libhdf5-dev (libhdf5_fortran + hdf5.pc for pkg-config)
#   pkg-config                     apt: pkg-config
#   gnuplot                        apt: gnuplot-nox
#   fpm                            pip: python3 -m pip install fpm (the only source used for fpm)
#   numpy and h5py for python3     pip: python3 -m pip install numpy h5py (the Python reader in
#                                  python/ and its tests); apt: python3-numpy python3-h5py instead
#                                  when python3 is a distribution's own, externally managed Python
# With --slurm (or GAPBEAM_SETUP_SLURM=1), for scripts/test_slurm.sh, a single-node Slurm with
# accounting (sacct needs slurmdbd, which needs a MySQL server):
#   munged, munge                  apt: munge
#   slurmctld, slurmd              apt: slurmctld slurmd
#   sbatch, squeue, scontrol, sacct, sacctmgr   apt: slurm-client
#   slurmdbd                       apt: slurmdbd
#   mariadbd, mariadb-install-db   apt: mariadb-server
# (on a machine with systemd, installing them may start their system services; the test runs its
# own daemons on free ports and never uses those)
# apt-get runs (with sudo when not root) only when something is missing: one `apt-get update`, then
# one `apt-get install`. Prints nothing when everything is there, else one `setup: installing ...`
# line per install step; the apt and pip output goes to a log file under ${TMPDIR:-/tmp}, shown when
# a step fails. Exits (or, when sourced, returns) non-zero with a message if an install fails.
# Idempotent. When executed it runs under `set -euo pipefail`; when sourced it leaves the caller's
# shell options alone (the work is done in functions that check every step themselves).

if [[ ${BASH_SOURCE[0]} == "$0" ]]; then
   set -euo pipefail
fi

_gapbeam_setup_log=""
_gapbeam_setup_slurm=${GAPBEAM_SETUP_SLURM:-0}
if [[ ${1:-} == --slurm ]]; then _gapbeam_setup_slurm=1; fi

# True if command $1 exists.
_gapbeam_have() {
   command -v "$1" >/dev/null 2>&1
}

# True if daemon $1 exists (on PATH or in /usr/sbin, which a user's PATH may lack).
_gapbeam_have_daemon() {
   _gapbeam_have "$1" || [[ -x /usr/sbin/$1 ]]
}

# Print an error line on stderr.
_gapbeam_setup_error() {
   printf 'setup: error: %s\n' "$*" >&2
}

# Create the log file on first use; print its path.
_gapbeam_setup_logfile() {
   if [[ -z $_gapbeam_setup_log ]]; then
      _gapbeam_setup_log=$(mktemp "${TMPDIR:-/tmp}/gapbeam-setup-XXXXXX") || return 1
   fi
   printf '%s\n' "$_gapbeam_setup_log"
}

# Show the end of the log file on stderr (after a failed step).
_gapbeam_setup_show_log() {
   if [[ -n $_gapbeam_setup_log && -s $_gapbeam_setup_log ]]; then
      printf 'setup: last lines of %s:\n' "$_gapbeam_setup_log" >&2
      tail -n 30 "$_gapbeam_setup_log" | sed 's/^/    /' >&2
   fi
}

# True if the linker finds lib$1.so (asks gfortran; without gfortran looks in the usual places).
_gapbeam_have_lib() {
   local f
   if _gapbeam_have gfortran; then
      f=$(gfortran -print-file-name="lib$1.so" 2>/dev/null) || return 1
      [[ $f == /* && -e $f ]]
   else
      compgen -G "/usr/lib/*/lib$1.so" >/dev/null || compgen -G "/usr/lib/lib$1.so" >/dev/null \
         || compgen -G "/usr/local/lib/lib$1.so" >/dev/null
   fi
}

# Print the pkg-config name of HDF5 (hdf5 or hdf5-serial); false if pkg-config does not know it.
_gapbeam_hdf5_pc() {
   local pc
   _gapbeam_have pkg-config || return 1
   for pc in hdf5 hdf5-serial; do
      if pkg-config --exists "$pc" 2>/dev/null; then
         printf '%s\n' "$pc"
         return 0
      fi
   done
   return 1
}

# True if the HDF5 Fortran library is installed, and (when pkg-config is here) pkg-config knows
# HDF5, as fpm's hdf5 metapackage needs.
_gapbeam_have_hdf5_fortran() {
   local pc flag
   if _gapbeam_have pkg-config; then
      pc=$(_gapbeam_hdf5_pc) || return 1
      for flag in $(pkg-config --libs-only-L "$pc" 2>/dev/null); do
         [[ -e ${flag#-L}/libhdf5_fortran.so ]] && return 0
      done
   fi
   compgen -G '/usr/lib/*/hdf5/serial/libhdf5_fortran.so' >/dev/null \
      || compgen -G '/usr/lib/*/libhdf5_fortran.so' >/dev/null \
      || compgen -G '/usr/lib/libhdf5_fortran.so' >/dev/null
}

# True if python3 imports numpy and h5py (the Python reader in python/ needs them).
_gapbeam_have_python_modules() {
   _gapbeam_have python3 && python3 -c 'import numpy, h5py' >/dev/null 2>&1
}

# True if python3 is a distribution's own Python that pip refuses to install into (PEP 668: an
# EXTERNALLY-MANAGED marker, and not a virtual environment); its packages come from apt.
_gapbeam_python_is_external() {
   _gapbeam_have python3 && python3 -c 'import os, sys, sysconfig
marker = os.path.join(sysconfig.get_path("stdlib"), "EXTERNALLY-MANAGED")
sys.exit(0 if os.path.isfile(marker) and sys.prefix == sys.base_prefix else 1)' >/dev/null 2>&1
}

# Print the apt packages for what is missing, one per line.
_gapbeam_missing_apt() {
   _gapbeam_have gfortran || printf '%s\n' gfortran
   if ! _gapbeam_have gfortran || ! _gapbeam_have_lib lapack || ! _gapbeam_have_lib blas; then
      printf '%s\n' liblapack-dev libopenblas-dev
   fi
   _gapbeam_have_hdf5_fortran || printf '%s\n' libhdf5-dev
   _gapbeam_have pkg-config || printf '%s\n' pkg-config
   _gapbeam_have gnuplot || printf '%s\n' gnuplot-nox
   if _gapbeam_python_is_external && ! _gapbeam_have_python_modules; then
      printf '%s\n' python3-numpy python3-h5py
   fi
   if [[ $_gapbeam_setup_slurm == 1 ]]; then
      { _gapbeam_have_daemon munged && _gapbeam_have munge; } || printf '%s\n' munge
      _gapbeam_have_daemon slurmctld || printf '%s\n' slurmctld
      _gapbeam_have_daemon slurmd || printf '%s\n' slurmd
      { _gapbeam_have sbatch && _gapbeam_have sacct && _gapbeam_have sacctmgr; } \
         || printf '%s\n' slurm-client
      _gapbeam_have_daemon slurmdbd || printf '%s\n' slurmdbd
      { _gapbeam_have_daemon mariadbd && _gapbeam_have mariadb-install-db; } \
         || printf '%s\n' mariadb-server
   fi
}

# Install the missing apt packages (if any).
_gapbeam_setup_apt() {
   local -a pkgs sudo_cmd=()
   local log still
   mapfile -t pkgs < <(_gapbeam_missing_apt)
   [[ ${#pkgs[@]} -gt 0 ]] || return 0

   if ! _gapbeam_have apt-get; then
      _gapbeam_setup_error "missing ${pkgs[*]}, and there is no apt-get here to install them;" \
         "install gfortran, LAPACK/BLAS, HDF5 (with Fortran), pkg-config and gnuplot by hand"
      return 1
   fi
   if [[ $(id -u) -ne 0 ]]; then
      if _gapbeam_have sudo; then
         sudo_cmd=(sudo)
      else
         _gapbeam_setup_error "missing ${pkgs[*]}; not root and no sudo: as root run" \
            "apt-get update && apt-get install -y ${pkgs[*]}"
         return 1
      fi
   fi
   log=$(_gapbeam_setup_logfile) || { _gapbeam_setup_error "cannot create a log file"; return 1; }

   printf 'setup: installing %s (apt-get, log %s)\n' "${pkgs[*]}" "$log"
   if ! "${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive \
         apt-get -q -o DPkg::Lock::Timeout=300 update >>"$log" 2>&1; then
      _gapbeam_setup_show_log
      _gapbeam_setup_error "apt-get update failed (log $log)"
      return 1
   fi
   if ! "${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive \
         apt-get -q -y --no-install-recommends -o DPkg::Lock::Timeout=300 \
         install "${pkgs[@]}" >>"$log" 2>&1; then
      _gapbeam_setup_show_log
      _gapbeam_setup_error "apt-get install ${pkgs[*]} failed (log $log)"
      return 1
   fi
   hash -r
   still=$(_gapbeam_missing_apt | tr '\n' ' ')
   if [[ -n $still ]]; then
      _gapbeam_setup_error "still missing after apt-get install: $still(log $log)"
      return 1
   fi
}

# True if `fpm` runs from PATH; otherwise look in the places pip and pyenv put scripts and, if it
# runs from one of them, prepend that folder to PATH (exported).
_gapbeam_find_fpm() {
   local d
   local -a dirs=()
   if _gapbeam_have fpm && fpm --version >/dev/null 2>&1; then
      return 0
   fi
   if _gapbeam_have python3; then
      d=$(python3 -m site --user-base 2>/dev/null) && dirs+=("$d/bin")
      while IFS= read -r d; do
         [[ -n $d ]] && dirs+=("$d")
      done < <(python3 -c 'import os, sysconfig
print(sysconfig.get_path("scripts"))
print(sysconfig.get_path("scripts", os.name + "_user"))' 2>/dev/null || true)
   fi
   if _gapbeam_have pyenv; then
      d=$(pyenv root 2>/dev/null) && dirs+=("$d/shims")
   fi
   dirs+=("${PYENV_ROOT:-${HOME:-}/.pyenv}/shims" "${HOME:-}/.local/bin")
   for d in "${dirs[@]}"; do
      if [[ -x $d/fpm ]] && "$d/fpm" --version >/dev/null 2>&1; then
         export PATH="$d:$PATH"
         hash -r
         return 0
      fi
   done
   return 1
}

# Make sure fpm runs; install it with pip if it is nowhere.
_gapbeam_setup_fpm() {
   local log
   _gapbeam_find_fpm && return 0
   if ! _gapbeam_have python3; then
      _gapbeam_setup_error "fpm is missing and so is python3 (fpm is installed with pip)"
      return 1
   fi
   if ! python3 -m pip --version >/dev/null 2>&1; then
      _gapbeam_setup_error "fpm is missing and python3 has no pip (python3 -m pip);" \
         "install pip, e.g. apt-get install python3-pip, then run this again"
      return 1
   fi
   log=$(_gapbeam_setup_logfile) || { _gapbeam_setup_error "cannot create a log file"; return 1; }
   printf 'setup: installing fpm (python3 -m pip install fpm, log %s)\n' "$log"
   if ! python3 -m pip install --disable-pip-version-check fpm >>"$log" 2>&1; then
      # A distribution's own Python refuses (PEP 668); fpm is one self-contained program, so a
      # user install beside the system packages is safe.
      if grep -q 'externally-managed-environment' "$log" \
         && python3 -m pip install --disable-pip-version-check --user --break-system-packages \
               fpm >>"$log" 2>&1; then
         :
      else
         _gapbeam_setup_show_log
         _gapbeam_setup_error "python3 -m pip install fpm failed (log $log)"
         return 1
      fi
   fi
   if _gapbeam_have pyenv; then
      pyenv rehash >>"$log" 2>&1 || true
   fi
   hash -r
   if ! _gapbeam_find_fpm; then
      _gapbeam_setup_error "pip installed fpm but it cannot be found or run; looked on PATH," \
         "in \$(python3 -m site --user-base)/bin, the Python scripts folders and pyenv shims"
      return 1
   fi
}

# Make sure python3 imports numpy and h5py; install them with pip where they are missing (an
# externally managed python3 got them from apt in _gapbeam_setup_apt).
_gapbeam_setup_python() {
   local log
   _gapbeam_have_python_modules && return 0
   if ! _gapbeam_have python3; then
      _gapbeam_setup_error "python3 is missing (the Python reader in python/ and its tests need" \
         "python3 with numpy and h5py)"
      return 1
   fi
   if ! python3 -m pip --version >/dev/null 2>&1; then
      _gapbeam_setup_error "numpy or h5py is missing and python3 has no pip (python3 -m pip);" \
         "install pip, e.g. apt-get install python3-pip, then run this again"
      return 1
   fi
   log=$(_gapbeam_setup_logfile) || { _gapbeam_setup_error "cannot create a log file"; return 1; }
   printf 'setup: installing numpy h5py (python3 -m pip install numpy h5py, log %s)\n' "$log"
   if ! python3 -m pip install --disable-pip-version-check numpy h5py >>"$log" 2>&1; then
      _gapbeam_setup_show_log
      _gapbeam_setup_error "python3 -m pip install numpy h5py failed (log $log)"
      return 1
   fi
   if ! _gapbeam_have_python_modules; then
      _gapbeam_setup_error "pip installed numpy and h5py but python3 cannot import them (log $log)"
      return 1
   fi
}

_gapbeam_setup_main() {
   local path_before=$PATH
   _gapbeam_setup_apt || return 1
   _gapbeam_setup_fpm || return 1
   _gapbeam_setup_python || return 1
   if [[ ${BASH_SOURCE[0]} == "$0" && $PATH != "$path_before" ]]; then
      printf 'setup: fpm is in %s, which is not on your PATH; add it (run.sh and test.sh do)\n' \
         "$(dirname "$(command -v fpm)")"
   fi
   return 0
}

_gapbeam_setup_status=0
_gapbeam_setup_main || _gapbeam_setup_status=$?

# fpm's incremental build keeps what it built from sources that have since moved or changed
# interface: an object of a moved module stays in the library archive (`ar` adds and replaces
# members, never removes them), and the test helper modules are not rebuilt when a type of src/
# changes. When the sources differ from those of the last build (a digest of src/, app/, test/),
# drop the archives and the test objects, so that fpm re-archives and rebuilds them (seconds).
_gapbeam_drop_stale_build() {
   local here digest stamp
   here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd) || return 0
   [[ -d ${here}/build ]] || return 0
   digest=$(cd "${here}" && find src app test -name '*.f90' -type f 2>/dev/null | LC_ALL=C sort \
      | xargs cat -- 2>/dev/null | cksum) || return 0
   stamp=${here}/build/.gapbeam-sources
   if [[ ! -f ${stamp} || $(cat "${stamp}") != "${digest}" ]]; then
      rm -f "${here}"/build/gfortran_*/gapbeam/libgapbeam.a "${here}"/build/gfortran_*/gapbeam/test_*.o \
         "${here}"/build/gfortran_*/gapbeam/test_*.o.digest 2>/dev/null
      printf '%s\n' "${digest}" >"${stamp}" 2>/dev/null || true
   fi
   return 0
}
_gapbeam_drop_stale_build
if [[ ${BASH_SOURCE[0]} != "$0" ]]; then
   unset -f _gapbeam_have _gapbeam_setup_error _gapbeam_setup_logfile _gapbeam_setup_show_log \
      _gapbeam_have_lib _gapbeam_hdf5_pc _gapbeam_have_hdf5_fortran _gapbeam_missing_apt \
      _gapbeam_setup_apt _gapbeam_find_fpm _gapbeam_setup_fpm _gapbeam_have_python_modules \
      _gapbeam_python_is_external _gapbeam_setup_python _gapbeam_setup_main _gapbeam_have_daemon \
      _gapbeam_drop_stale_build
   unset _gapbeam_setup_log _gapbeam_setup_slurm
fi
# The status of the last command is that of the script (executed) or of `source` (sourced); a
# subshell's exit, so that a sourcing shell is never ended here.
(exit "${_gapbeam_setup_status}")
