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
!> creates that directory when missing.
module gapbeam_output_set
   use gapbeam_error, only: error_t, fatal_error, str
   use gapbeam_files, only: rename_file, remove_file, file_exists, directory_exists, &
      make_parent_directory, process_id
   use gapbeam_hdf5_output, only: h5_writer_t
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
   contains
      procedure :: begin => set_begin              !! name the files; make the directory
      procedure :: temp => set_temp                !! temporary name of file k
      procedure :: final_name => set_final_name    !! final name of file k
      procedure :: names => set_names              !! file names without the directory
      procedure :: size => set_size                !! number of files
      procedure :: record => set_record            !! the list of files, in an HDF5 file
      procedure :: commit => set_commit            !! put every file in place, or none
      procedure :: discard => set_discard          !! remove the temporaries
      procedure :: finish => set_finish            !! commit, or discard after an error
   end type output_set_t

   character(len=*), parameter :: here = 'gapbeam_output_set: '

contains

   !> Name the files of the set, PREFIX // suffix for each suffix ('.h5', '.history.dat', ...),
   !> and create the directory of PREFIX when missing. The `.h5` file should come first: it is
   !> put in place last.
   subroutine set_begin(self, prefix, suffixes, err)
      class(output_set_t), intent(out) :: self           !! the set
      character(len=*), intent(in) :: prefix             !! output prefix
      character(len=*), intent(in) :: suffixes(:)        !! one per file, e.g. ['.h5  ', '.dat ']
      type(error_t), allocatable, intent(out) :: err     !! the directory cannot be made
      integer :: k
      self%prefix = trim(prefix)
      self%tag = '.' // str(process_id())
      allocate(self%final(size(suffixes)))
      do k = 1, size(suffixes)
         self%final(k)%s = self%prefix // trim(suffixes(k))
      end do
      call make_parent_directory(self%prefix, err)
   end subroutine set_begin

   !> The temporary name file k is written under, 'FINAL.<pid>.part'.
   function set_temp(self, k) result(name)
      class(output_set_t), intent(in) :: self            !! the set
      integer, intent(in) :: k                           !! file number, as given to begin
      character(len=:), allocatable :: name
      name = self%final(k)%s // self%tag // '.part'
   end function set_temp

   !> The final name of file k.
   function set_final_name(self, k) result(name)
      class(output_set_t), intent(in) :: self            !! the set
      integer, intent(in) :: k                           !! file number, as given to begin
      character(len=:), allocatable :: name
      name = self%final(k)%s
   end function set_final_name

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

   !> Write the list of the set's files (names without directory) to `/run/files` of an HDF5
   !> file being written, with a `description` attribute.
   subroutine set_record(self, h5, err)
      class(output_set_t), intent(in) :: self            !! the set
      type(h5_writer_t), intent(inout) :: h5             !! writer of the set's HDF5 file
      type(error_t), allocatable, intent(out) :: err     !! write failure
      character(len=:), allocatable :: names(:)
      call self%names(names)
      call h5%write('/run/files', names, '1', err, 'the files written together with this ' &
         // 'one, in its directory, by one run (they appear together or not at all)')
      if (allocated(err)) return
      call h5%write_attr('/run/files', 'description', 'the files written together with this ' &
         // 'one, in its directory, by one run (they appear together or not at all)', err)
   end subroutine set_record

   !> After the writers: commit the set when `err` is not set, else discard it (`err` kept).
   subroutine set_finish(self, err)
      class(output_set_t), intent(inout) :: self         !! the set
      type(error_t), allocatable, intent(inout) :: err   !! the writers' status; the commit's
      if (allocated(err)) then
         call self%discard()
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

   !> The name a previous run's file k is moved aside to during the commit.
   function old_name(self, k) result(name)
      type(output_set_t), intent(in) :: self             !! the set
      integer, intent(in) :: k                           !! file number
      character(len=:), allocatable :: name
      name = self%final(k)%s // self%tag // '.old'
   end function old_name

   !> Text in single quotes.
   pure function q(s) result(quoted)
      character(len=*), intent(in) :: s                  !! text
      character(len=:), allocatable :: quoted
      quoted = "'" // s // "'"
   end function q
end module gapbeam_output_set
