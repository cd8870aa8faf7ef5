/* file_guard: the run's files as a careful batch tool makes them.
 *
 *  - a private folder per run (mkdtemp under $TMPDIR or /tmp) for gmsh's
 *    meshes and logs, removed at exit and on SIGINT, SIGTERM, SIGHUP;
 *  - output temporaries made in the output folder with O_CREAT|O_EXCL (no
 *    symbolic link followed) under unique names, removed at exit and on
 *    those signals unless committed; the signal handler also kills the
 *    running gmsh group (process_runner.h) and then re-raises the signal;
 *  - inputs opened without blocking and refused unless regular files;
 *  - folders made with mkdir(2), parents too;
 *  - an exclusive flock on the output folder for the commit of the outputs.
 *
 * Files are handed to Fortran as descriptors: Fortran opens
 * /proc/self/fd/N, which reaches the very file the descriptor refers to
 * (no path is looked up again). */
#ifndef CONTACT2D_FILE_GUARD_H
#define CONTACT2D_FILE_GUARD_H

/* file kinds (c2d_file_kind, c2d_open_input) */
enum { C2D_REGULAR = 0, C2D_MISSING = 1, C2D_FIFO = 2, C2D_DEVICE = 3, C2D_FOLDER = 4, C2D_SOCKET = 5,
       C2D_UNREADABLE = 6 };

/* Kind of the file at path (symbolic links followed: stat). */
int c2d_file_kind(const char *path);

/* Open path for reading only when it is a regular file: stat first, then
 * open with O_NONBLOCK (a FIFO swapped in meanwhile cannot block) and fstat
 * the descriptor.  Returns a file kind; *fd >= 0 only for C2D_REGULAR. */
int c2d_open_input(const char *path, int *fd);

/* close(2); 0 or errno. */
int c2d_close(int fd);

/* mkdir path and its missing parents (mode 0777 & ~umask).  0 or errno
 * (ENOTDIR when a component is not a folder). */
int c2d_make_folders(const char *path);

/* The run's private folder, made on the first call.  path: (len) receives
 * it.  Returns its length, or -errno. */
int c2d_private_folder(char *path, int len);

/* A new output temporary in folder dir for the output `name`:
 * dir/.name~XXXXXX (a '~' no OUTPUT name may hold), mode 0666 & ~umask.
 * path: (len) receives its name; *fd its descriptor.  It is removed at exit
 * unless c2d_forget_temporary is called.  Returns 0 or errno. */
int c2d_create_temporary(const char *dir, const char *name, char *path, int len, int *fd);

/* The temporary at path is no longer the run's to remove (renamed into
 * place, or removed by the caller). */
void c2d_forget_temporary(const char *path);

/* Exclusive flock on folder dir, waiting for another run's to end.  Returns
 * the descriptor (>= 0) or -errno.  Also defers SIGINT/SIGTERM/SIGHUP
 * cleanup until c2d_unlock_folder, so a commit is never cut in half. */
int c2d_lock_folder(const char *dir);

/* Release the lock of c2d_lock_folder; a signal that arrived meanwhile is
 * acted on now. */
void c2d_unlock_folder(int fd);

/* Size and modification time (nanoseconds since the epoch) of path, links
 * followed: a stamp that changes when the file is replaced (a program
 * upgraded).  0, or errno. */
int c2d_file_stamp(const char *path, long long *size, long long *mtime_ns);

/* realpath(3): 0 and the path, or errno. */
int c2d_real_path(const char *path, char *real, int len);

#endif
