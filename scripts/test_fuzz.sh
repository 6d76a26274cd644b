#!/usr/bin/env bash
# scripts/test_fuzz.sh - the deck fuzz test (scripts/fuzz_decks.py) on a gapbeam executable.
#
# Usage:
#   scripts/test_fuzz.sh GAPBEAM_EXE [FUZZ_DECKS_OPTION ...]
#   (meant to be called by scripts/test.sh with the debug-built executable, like test_cli.sh)
#
# Runs `python3 scripts/fuzz_decks.py GAPBEAM_EXE` with its defaults (seed 20240611, 24 decks per
# mutation class (20 classes) plus the unmutated cheap decks of inputs/, 2 workers, 5 s per deck,
# 60 s for the whole run) and any extra options given. It prints one `PASS  fuzz: ...` or `FAIL  fuzz: ...` line per
# mutation class and one for the run time, then tables of counts; see the header of
# scripts/fuzz_decks.py for the mutation classes and how each run is classified.
#
# Environment:
#   GAPBEAM_FUZZ_SEED   seed (default: fuzz_decks.py's, 20240611)
#   GAPBEAM_FUZZ_JOBS   parallel runs (default 2)
# Exit status: that of fuzz_decks.py (1 if any check failed), or 1 without python3.
set -euo pipefail

if [[ $# -lt 1 || ${1:-} == -h || ${1:-} == --help ]]; then
   printf 'usage: %s GAPBEAM_EXE [FUZZ_DECKS_OPTION ...]\n' "$0" >&2
   exit 2
fi
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
exe=$1
shift
if ! command -v python3 >/dev/null 2>&1; then
   printf 'FAIL  fuzz: python3 is not installed\n'
   exit 1
fi
args=()
if [[ -n ${GAPBEAM_FUZZ_SEED:-} ]]; then args+=(--seed "${GAPBEAM_FUZZ_SEED}"); fi
args+=(--jobs "${GAPBEAM_FUZZ_JOBS:-2}")
exec python3 "${root}/scripts/fuzz_decks.py" "${exe}" "${args[@]}" "$@"
