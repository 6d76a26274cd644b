!> The files of one run appear together or not at all.
!>
!> A run's result files (PREFIX.h5 and its text tables) form an output set. Every file is first
!> written under a temporary name unique to the process, `FINAL.<pid>.part`; only when all are
!> complete does `commit` put them in place:
!>
!> 1. each file of the set that exists already (a previous run's) is moved aside to
!>    `FINAL.<pid>.old`;
!> 2. each temporary is renamed to its final name, the text tables first and PREFIX.h5 last;
!> 3. the moved-aside files are deleted.
!>
!> If any step fails, the new files are removed and the moved-aside ones are put back: the
!> previous complete set is left as it was, and the error says what failed. A writer that
!> fails before the commit calls `discard`, which removes the temporaries. A run killed during
!> the commit (a few renames) can leave `.part` or `.old` files of its process id, but never a
!> new PREFIX.h5 beside old tables: PREFIX.h5 is renamed last, and it lists the files of its
!> set (`names`, written to `/run/files` by the writers).
!>
!> All files of a set share the directory of PREFIX (so that renames are atomic); `begin`
!> creates that directory when missing, and refuses a PREFIX that names a directory
!> ('results/x/', '.', '..': its files would be hidden, 'results/x/.h5').
!>
!> Errors are a state of the set, as of the HDF5 writer: the first failure of any step is
!> kept, later steps do nothing, and `finish` reports it after removing the temporaries.
!>
!> ```fortran
!> call set%begin(prefix, [character(len=12) :: '.h5', '.history.dat'])
!> call set%open_h5(h5, 'transient', deck%text)     ! root attributes, /deck, /run/files
!> call h5%put('/history/time', time)
!> call set%close_h5(h5)
!> call set%table('.history.dat', title, names, units, columns)
!> call set%finish(err)                              ! all in place, or nothing changed
!> ```
module gapbeam_output_set
   use gapbeam_error, only: error_t, fatal_error, str, q => quoted
   use gapbeam_kinds, only: dp
   use gapbeam_files, only: rename_file, remove_file, file_exists, directory_exists, &
      make_parent_directory, process_id, write_table, write_text_file
   use gapbeam_deck_rules, only: output_prefix_problem
   use gapbeam_hdf5_output, only: h5_writer_t
   use gapbeam_file_info, only: write_file_info
   implicit none
   private
   public :: output_set_t

   !> A file name of any length.
   type :: name_t
      character(len=:), allocatable :: s   !! the name
   end type name_t

   !> The files of one run: their final names and the temporary names they are written under.
   type :: output_set_t
      private
      character(len=:), allocatable :: prefix      !! output prefix, e.g. 'results/baseline'
      character(len=:), allocatable :: tag         !! '.<pid>', unique to the process
      type(name_t), allocatable :: final(:)        !! final names, in the order given
      type(error_t), allocatable :: err            !! the first failure
   contains
      procedure :: begin => set_begin              !! name the files; make the directory
      procedure :: temp => set_temp                !! temporary name of file k
      procedure :: names => set_names              !! file names without the directory
      procedure :: size => set_size                !! number of files
      procedure :: open_h5 => set_open_h5          !! the .h5: root attributes, /deck, /run/files
      procedure :: close_h5 => set_close_h5        !! close the .h5, keeping its failure
      procedure :: table => set_table              !! a gnuplot table of the set
      procedure :: text => set_text                !! a text file of the set
      procedure :: keep => set_keep                !! keep a failure found by the caller
      procedure :: failed => set_failed            !! whether a step failed
      procedure :: commit => set_commit            !! put every file in place, or none
      procedure :: discard => set_discard          !! remove the temporaries
      procedure :: finish => set_finish            !! commit, or discard after a failure
   end type output_set_t

   character(len=*), parameter :: here = 'gapbeam_output_set: '

contains

   !> Name the files of the set, PREFIX // suffix for each suffix ('.h5', '.history.dat', ...),
   !> and create the directory of PREFIX when missing. The `.h5` file should come first: it is
   !> put in place last.
   subroutine set_begin(self, prefix, suffixes)
      class(output_set_t), intent(out) :: self           !! the set
      character(len=*), intent(in) :: prefix             !! output prefix
      character(len=*), intent(in) :: suffixes(:)        !! one per file, e.g. ['.h5  ', '.dat ']
      character(len=:), allocatable :: why
      integer :: k
      self%prefix = trim(prefix)
      self%tag = '.' // str(process_id())
      allocate(self%final(size(suffixes)))
      do k = 1, size(suffixes)
         self%final(k)%s = self%prefix // trim(suffixes(k))
      end do
      why = output_prefix_problem(self%prefix)
      if (len(why) > 0) then
         call fatal_error(self%err, here // why)
         return
      end if
      call make_parent_directory(self%prefix, self%err)
   end subroutine set_begin

   !> The temporary name file k is written under, 'FINAL.<pid>.part'.
   function set_temp(self, k) result(name)
      class(output_set_t), intent(in) :: self            !! the set
      integer, intent(in) :: k                           !! file number, as given to begin
      character(len=:), allocatable :: name
      name = self%final(k)%s // self%tag // '.part'
   end function set_temp

   !> Number of files in the set.
   pure integer function set_size(self)
      class(output_set_t), intent(in) :: self            !! the set
      set_size = 0
      if (allocated(self%final)) set_size = size(self%final)
   end function set_size

   !> The final names without their directory, for the list a result file keeps of its set.
   !> (A subroutine: gfortran 12 fails to compile a type-bound function with this result.)
   subroutine set_names(self, names)
      class(output_set_t), intent(in) :: self            !! the set
      character(len=:), allocatable, intent(out) :: names(:)   !! one per file
      integer :: k, width, slash
      width = 1
      do k = 1, self%size()
         slash = index(self%final(k)%s, '/', back=.true.)
         width = max(width, len(self%final(k)%s) - slash)
      end do
      allocate(character(len=width) :: names(self%size()))
      do k = 1, self%size()
         slash = index(self%final(k)%s, '/', back=.true.)
         names(k) = self%final(k)%s(slash + 1:)
      end do
   end subroutine set_names

   !> Create the set's HDF5 file (its first file, under its temporary name) for `analysis`,
   !> with the root attributes, /deck, /run/files (the files of the set, without their
   !> directory) and /run/warnings (the run's warnings; empty when there are none). Nothing
   !> when a step failed already.
   subroutine set_open_h5(self, h5, analysis, deck_text, warnings)
      class(output_set_t), intent(in) :: self            !! the set; file 1 is the .h5
      type(h5_writer_t), intent(inout) :: h5             !! writer, not open
      character(len=*), intent(in) :: analysis           !! analysis word
      character(len=*), intent(in) :: deck_text          !! the effective deck text
      character(len=*), intent(in), optional :: warnings(:)   !! one line each
      character(len=:), allocatable :: names(:)
      character(len=1) :: none(0)
      character(len=*), parameter :: description = 'the files written together with this ' &
         // 'one, in its directory, by one run (they appear together or not at all)'
      if (allocated(self%err)) return
      call h5%create(self%temp(1), analysis, in_place=.true.)
      call write_file_info(h5, analysis, deck_text)
      call h5%put('/deck', deck_text)
      call self%names(names)
      call h5%put('/run/files', names)
      call h5%attr('/run/files', 'description', description)
      if (present(warnings)) then
         call put_lines(h5, '/run/warnings', warnings)
      else
         call h5%put('/run/warnings', none)
      end if
   end subroutine set_open_h5

   !> Lines as a string dataset as wide as the longest of them (trailing blanks dropped).
   subroutine put_lines(h5, path, lines)
      type(h5_writer_t), intent(inout) :: h5             !! open writer
      character(len=*), intent(in) :: path               !! dataset
      character(len=*), intent(in) :: lines(:)           !! one line each
      character(len=:), allocatable :: cut(:)
      integer :: k, width
      width = 1
      do k = 1, size(lines)
         width = max(width, len_trim(lines(k)))
      end do
      allocate(character(len=width) :: cut(size(lines)))
      do k = 1, size(lines)
         cut(k) = lines(k)
      end do
      call h5%put(path, cut)
   end subroutine put_lines

   !> Close the set's HDF5 file; its failure (of any of its calls) becomes the set's.
   subroutine set_close_h5(self, h5)
      class(output_set_t), intent(inout) :: self         !! the set
      type(h5_writer_t), intent(inout) :: h5             !! writer of file 1
      type(error_t), allocatable :: e
      if (allocated(self%err)) then
         call h5%abort()
         return
      end if
      call h5%close(e)
      if (allocated(e)) call move_alloc(e, self%err)
   end subroutine set_close_h5

   !> Write the gnuplot table PREFIX // suffix of the set (gapbeam_files: write_table).
   subroutine set_table(self, suffix, title, names, units, columns)
      class(output_set_t), intent(inout) :: self         !! the set
      character(len=*), intent(in) :: suffix             !! which file, e.g. '.history.dat'
      character(len=*), intent(in) :: title              !! first comment line
      character(len=*), intent(in) :: names(:), units(:) !! column names and units
      real(dp), intent(in) :: columns(:, :)              !! (rows, columns)
      if (allocated(self%err)) return
      call write_table(self%temp(which(self, suffix)), title, names, units, columns, self%err)
   end subroutine set_table

   !> Write the text file PREFIX // suffix of the set.
   subroutine set_text(self, suffix, text)
      class(output_set_t), intent(inout) :: self         !! the set
      character(len=*), intent(in) :: suffix             !! which file, e.g. '.stability.txt'
      character(len=*), intent(in) :: text               !! its contents
      if (allocated(self%err)) return
      call write_text_file(self%temp(which(self, suffix)), text, self%err)
   end subroutine set_text

   !> Keep a failure the caller found (the first one is kept).
   subroutine set_keep(self, e)
      class(output_set_t), intent(inout) :: self         !! the set
      type(error_t), intent(in) :: e                     !! the failure
      if (.not. allocated(self%err)) self%err = e
   end subroutine set_keep

   !> Whether a step of the set failed.
   pure logical function set_failed(self)
      class(output_set_t), intent(in) :: self            !! the set
      set_failed = allocated(self%err)
   end function set_failed

   !> After the writers: commit the set, or discard it after a failure (reported in `err`).
   subroutine set_finish(self, err)
      class(output_set_t), intent(inout) :: self         !! the set
      type(error_t), allocatable, intent(out) :: err     !! the first failure, or the commit's
      if (allocated(self%err)) then
         call self%discard()
         call move_alloc(self%err, err)
         return
      end if
      call self%commit(err)
   end subroutine set_finish

   !> Put every file in place, the first (the .h5) last; on any failure restore the previous
   !> set and remove the new files (see the module header). The temporaries must all exist.
   subroutine set_commit(self, err)
      class(output_set_t), intent(inout) :: self         !! the set, every file written
      type(error_t), allocatable, intent(out) :: err     !! what failed; nothing changed then
      type(error_t), allocatable :: e
      logical, allocatable :: moved(:), placed(:)
      integer :: k, n, j
      integer, allocatable :: order(:)
      n = self%size()
      allocate(moved(n), placed(n), source=.false.)
      order = [(k, k = 2, n), 1]          ! the text files first, the .h5 last
      if (n == 1) order = [1]
      ! 1. move the previous run's files aside
      do k = 1, n
         if (.not. file_exists(self%final(k)%s)) cycle
         if (directory_exists(self%final(k)%s)) then
            call fatal_error(err, here // 'cannot replace ' // q(self%final(k)%s) &
               // ': it is a directory')
            exit
         end if
         call rename_file(self%final(k)%s, old_name(self, k), e)
         if (allocated(e)) then
            call fatal_error(err, here // 'cannot move the previous ' // q(self%final(k)%s) &
               // ' aside: ' // e%message)
            deallocate(e)
            exit
         end if
         moved(k) = .true.
      end do
      ! 2. the new files in place
      if (.not. allocated(err)) then
         do j = 1, n
            k = order(j)
            call rename_file(self%temp(k), self%final(k)%s, e)
            if (allocated(e)) then
               call fatal_error(err, here // 'cannot put ' // q(self%final(k)%s) // ' in place: ' &
                  // e%message)
               deallocate(e)
               exit
            end if
            placed(k) = .true.
         end do
      end if
      if (allocated(err)) then
         ! undo: remove what was placed, put the previous files back, drop the temporaries
         do k = 1, n
            if (placed(k)) call remove_file(self%final(k)%s)
            if (moved(k)) call rename_file(old_name(self, k), self%final(k)%s, e)
            if (allocated(e)) then
               err%message = err%message // '; and restoring the previous file failed too: ' &
                  // e%message // ' (it is kept as ' // q(old_name(self, k)) // ')'
               deallocate(e)
            end if
         end do
         call self%discard()
         err%message = err%message // '; the previous results under ' // q(self%prefix) &
            // ' are left as they were'
         return
      end if
      ! 3. the previous files are no longer needed
      do k = 1, n
         if (moved(k)) call remove_file(old_name(self, k))
      end do
   end subroutine set_commit

   !> Remove the temporaries of the set (after a failure); never fails.
   subroutine set_discard(self)
      class(output_set_t), intent(inout) :: self         !! the set
      integer :: k
      do k = 1, self%size()
         call remove_file(self%temp(k))
      end do
   end subroutine set_discard

   !> The number of the file PREFIX // suffix (a suffix not in the set is a programming error).
   integer function which(self, suffix)
      class(output_set_t), intent(in) :: self
      character(len=*), intent(in) :: suffix
      do which = 1, self%size()
         if (self%final(which)%s == self%prefix // trim(suffix)) return
      end do
      error stop 'gapbeam_output_set: a file that is not in the set'
   end function which

   !> The name a previous run's file k is moved aside to during the commit.
   function old_name(self, k) result(name)
      type(output_set_t), intent(in) :: self             !! the set
      integer, intent(in) :: k                           !! file number
      character(len=:), allocatable :: name
      name = self%final(k)%s // self%tag // '.old'
   end function old_name
end module gapbeam_output_set
