!> What `gapbeam --help` and `gapbeam --version` print, and the short usage of a bad command
!> line.
module gapbeam_usage
   use gapbeam_settings, only: analysis_words
   use gapbeam_version, only: program_version, compiler_text, git_commit
   use gapbeam_capability_text, only: capability_help
   implicit none
   private
   public :: usage_lines, help_text, version_text

   character(len=1), parameter :: nl = new_line('a')

contains

   !> The usage lines (also the start of the help).
   function usage_lines() result(t)
      character(len=:), allocatable :: t
      t = 'usage: gapbeam DECK [--shard I/N] [--shard-costs FILE.h5] [--time-limit S] [--quiet] ' &
         // '[--progress S] [OVERRIDE ...]' // nl &
         // '       gapbeam merge [--quiet] OUT.h5 SHARD.h5 ...' // nl &
         // '       gapbeam --help | --version | --help-deck [GROUP]' // nl &
         // '       gapbeam --help-outputs [ANALYSIS | tsv]'
   end function usage_lines

   !> The whole help text.
   function help_text() result(t)
      character(len=:), allocatable :: t
      t = 'gapbeam ' // program_version // ': finite element simulation of vibro-impact and ' &
         // 'chaotic vibration' // nl // 'of beams with gap supports (stops, snubbers, baffle ' &
         // 'clearances).' // nl // nl // usage_lines() // nl // nl &
         // '  DECK              a namelist deck; its &job analysis is one of' // nl &
         // '                    ' // analysis_words // nl &
         // '  OVERRIDE          a namelist fragment read after the deck, e.g.' // nl &
         // '                    "&forcing frequency_hz=10.2 /" (later values win)' // nl &
         // '  --shard I/N       run shard I of N of a sweep (then: gapbeam merge)' // nl &
         // '  --shard-costs F   deal the points to the shards by their costs in F.h5, an ' &
         // 'earlier' // nl // '                    sweep of the same grid (default: round ' &
         // 'robin)' // nl &
         // '  --time-limit S    stop a sweep cleanly after S seconds of wall time, ' &
         // 'checkpoint kept' // nl // '                    (so does SIGTERM, after the chunk ' &
         // 'in progress)' // nl &
         // '  --quiet, -q       no progress lines on standard error' // nl &
         // '  --progress S      seconds between progress lines (default: 1 on a terminal, ' &
         // 'where the' // nl &
         // '                    line is rewritten in place; 10 otherwise, one line each)' // nl &
         // '  merge             join the shard files of a sweep into OUT.h5' // nl &
         // '  --help, -h        this text;  --version, -V  version and build' // nl &
         // '  --help-deck [GROUP]  every deck variable (of one group): unit, default, what ' &
         // 'is allowed' // nl &
         // '  --help-outputs    every dataset the program writes: path, shape, units, ' &
         // 'meaning' // nl // '                    (of one analysis; tsv: one line each, ' &
         // 'tab-separated)' // nl // nl &
         // 'Results: PREFIX.h5 (HDF5, every dataset with units and long_name), gnuplot-ready ' &
         // 'PREFIX.*.dat' // nl &
         // 'tables, PREFIX.xdmf for ParaView (with &output state_history); PREFIX from &job ' &
         // 'output,' // nl // "default results/<deck name>. The last line of standard " &
         // "output is 'output: PREFIX'." // nl // nl &
         // 'Exit status: 0 done; 1 error (one line "error: ..." on standard error); 2 usage;' &
         // nl // '3 a sweep stopped by --time-limit (run the same command again to finish); ' &
         // '4 the output' // nl // 'prefix is locked by another run; 5 a sweep (or merge) ' &
         // 'wrote all its files but some of' // nl // 'its points failed (each listed on ' &
         // "standard error, label 'failed' in the files)." // nl // nl &
         // 'Environment: OMP_NUM_THREADS (sweep threads), OPENBLAS_NUM_THREADS (set it to 1), ' &
         // nl // 'GAPBEAM_BACKTRACE=1 (backtrace on errors), GAPBEAM_GIT_COMMIT (recorded in ' &
         // 'the HDF5' // nl // 'files; set by scripts/run.sh).' // nl // nl &
         // 'Documentation: README.md and docs/ in the source tree (docs/decks.md: every deck ' &
         // 'variable;' // nl // 'docs/outputs.md: every output dataset; docs/methods.md; ' &
         // 'docs/validation.md).'
   end function help_text

   !> The version text: version, compiler, commit.
   function version_text() result(t)
      character(len=:), allocatable :: t
      t = 'gapbeam ' // program_version // nl // 'compiler: ' // compiler_text() // nl &
         // 'commit: ' // git_commit()
   end function version_text
end module gapbeam_usage
