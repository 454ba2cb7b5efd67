#pragma once
/// \file output_file.hpp
/// Nothing lost: every output file is written to a temporary name in its directory and renamed
/// into place, an existing file is only replaced when the user said --force, and nothing a run
/// reads is ever replaced.
///
/// What an output path may name (the same rules for every verb's -o, --plot and simulate's log):
/// - nothing yet: created, and its missing parent directories with it (as `mkdir -p`; scripts
///   and the test suite rely on this). The name is claimed by a rename that fails when it
///   exists, so of two runs writing the same new name at once one wins and the other is refused;
/// - a regular file: replaced atomically, only with --force;
/// - a directory: refused, even with --force;
/// - an input of the run (note_input: the log, a saved result, a data sheet, a file in an
///   input folder), by device and inode, through any link: refused, even with --force;
/// - a character device, a FIFO or an open file descriptor (/dev/null, /dev/stdout, /dev/fd/N
///   as a process substitution gives): written straight into (open and write: no temporary
///   file, no rename), with or without --force, since that overwrites nothing;
/// - a socket or a block device: refused;
/// - a symbolic link: never replaced itself; it is followed (also when dangling) and the rules
///   above apply to its target, whose own directory then holds the temporary file (and is
///   created when missing).
/// A temporary name ("<target>.tmp-XXXXXX", "<dir>.partial-XXXXXX") is locked (flock) by its
/// writer for as long as it lives; one left by a run that died without cleaning up (kill -9, a
/// power cut) is removed by the next run writing the same target, a live run's never.

#include <filesystem>
#include <map>
#include <string>
#include <string_view>

namespace sigmatau {

/// Records a file or directory this run reads (a directory's files with it, one level: a rosbag2
/// folder), so that no output replaces it or, for an output directory, holds it. Paths that name
/// nothing, a device, a FIFO or stdin are not recorded (they are never replaced anyway).
/// Thread-safe.
void note_input(const std::filesystem::path& path);

/// Forgets every note_input (for tests, and a program that runs several jobs in one process).
void forget_inputs() noexcept;

/// Writes `content` to `path` by the rules above: for a new or regular file, writes
/// "<target>.tmp-<random>" beside the target (the path, or what its symbolic links lead to),
/// flushes it to disk and renames it over the target; for a device, FIFO or open descriptor,
/// writes straight into it. Throws Error (and leaves no temporary file behind) when the target
/// is a regular file and `overwrite` is false ("... exists; use --force to overwrite it"), a
/// directory, a socket or a block device, when its directory cannot be created or written, or
/// the disk is full (or the file-size limit is reached).
void write_file_atomically(const std::filesystem::path& path, std::string_view content,
                           bool overwrite);

/// Whether `path` (its symbolic links followed) is an output written straight into by the rules
/// above (a character device, a FIFO or an open descriptor: /dev/null, /dev/stdout, a process
/// substitution's /dev/fd/N), beside which no sibling file ("<path>.json") can go.
bool is_stream_output(const std::filesystem::path& path);

/// Throws, early, before long work starts, the Error write_file_atomically would throw for
/// `path` without writing anything: "exists; use --force", a directory, socket or block device,
/// a descriptor that is not open for writing, a device the user may not write, and
/// check_can_create_in's Error for a new or regular target. Never opens `path` (a FIFO would
/// block until its reader comes).
void check_can_write(const std::filesystem::path& path, bool overwrite);

/// Throws Error when nothing could be created at `path` (a trailing '/' ignored): its nearest
/// existing ancestor D is not writable and searchable ("cannot write PATH: <reason> (directory
/// D)") or is not a directory ("cannot create directory D: Not a directory"). Missing
/// directories in between are fine (they are created). Symbolic links of `path` itself are not
/// followed here (check_can_write and check_output_directory do that first). Called early, so
/// that a run does not fail only after its long work.
void check_can_create_in(const std::filesystem::path& path);

/// The file that marks a report directory as sigmatau's (analyze, demo -o DIR): its first line
/// is "sigmatau report directory", then comments (#), then the name of every file written, one
/// a line, relative to the directory.
inline constexpr const char* kReportMarker = ".sigmatau-report";

/// Checks an output DIRECTORY path (analyze and demo -o DIR) and returns where the directory
/// goes: `dir` with a trailing '/' removed and a symbolic link to it followed (a link is never
/// replaced). Throws Error when it exists and `overwrite` is false ("... exists; use --force to
/// replace it"); when, even with `overwrite`, it is an input of the run or holds one, is a file,
/// or is a directory other than an earlier report of sigmatau's (one holding the kReportMarker
/// file and no file it does not list, or, written before the marker, a results.json of
/// sigmatau's and only the file names analyze and demo gave then); when it is a device, FIFO,
/// socket or open descriptor; or when it could not be created (check_can_create_in). Creates
/// nothing.
std::filesystem::path check_output_directory(const std::filesystem::path& dir, bool overwrite);

/// Writes `files` (name relative to the directory -> content) as the directory `dir`, by the
/// rules of check_output_directory: built aside in a locked "<dir>.partial-XXXXXX" beside it with
/// the kReportMarker file, then renamed into place by a rename that fails when `dir` exists (two
/// runs at once: the second is refused), or, with `overwrite`, exchanged atomically with the
/// earlier report (checked again just before), which is then removed. Missing parents are
/// created. Throws Error (and leaves nothing behind) when any step fails.
void write_directory_atomically(const std::filesystem::path& dir,
                                const std::map<std::string, std::string>& files, bool overwrite);

/// Kills (SIGKILL) and reaps every child process a KillOnInterrupt tracks, then unlinks the
/// temporary file of every AtomicOutputFile that is open and not yet committed, then removes the
/// scratch paths an InterruptCleanup tracks (a directory with everything in it, to 8 levels),
/// and nothing else (the outputs themselves are never touched). Uses only async-signal-safe
/// calls, so a SIGINT / SIGTERM handler can call it before the process dies: an interrupted run
/// then leaves neither its output nor a partial "<path>.tmp-<random>" nor a scratch directory
/// behind. A temporary name longer than 4095 bytes, or more than 32 open at once, is not
/// tracked (it is still removed on the ordinary paths: commit, exception, destructor).
void remove_pending_temporaries() noexcept;

/// Puts a scratch file or directory of the run (not an output) on the same interrupt clean-up
/// table for as long as this object lives: remove_pending_temporaries() unlinks tracked files,
/// then removes tracked directories with whatever is in them (a finished plot, a child's log:
/// tracked by name or not), so only a directory the run owns whole may be tracked. The owner
/// still removes the path on the ordinary paths; this only covers a signal. Untracked silently
/// when the table is full.
class InterruptCleanup {
 public:
  explicit InterruptCleanup(const std::filesystem::path& path);
  ~InterruptCleanup();
  InterruptCleanup(const InterruptCleanup&) = delete;
  InterruptCleanup& operator=(const InterruptCleanup&) = delete;

 private:
  int slot_ = -1;
};

/// Puts a child process (gnuplot writing into a scratch directory) on the interrupt clean-up
/// table for as long as this object lives: remove_pending_temporaries() kills and reaps it first,
/// so that it writes nothing after its directory was removed, and it does not outlive a run
/// killed by SIGTERM or SIGHUP. Untracked silently when the table (8 children) is full. Destroy
/// it before the child is reaped (wait with waitid(WNOWAIT) first): a reaped child's PID may be
/// another process's by the time a signal comes.
class KillOnInterrupt {
 public:
  explicit KillOnInterrupt(int pid);
  ~KillOnInterrupt();
  KillOnInterrupt(const KillOnInterrupt&) = delete;
  KillOnInterrupt& operator=(const KillOnInterrupt&) = delete;

 private:
  int slot_ = -1;
};

/// A file written piece by piece (too large to hold as one string) that appears at `path` only
/// when commit() succeeds: it is written to "<target>.tmp-<random>" in the target's directory,
/// and the temporary file is removed if the object is destroyed before commit() (an exception
/// on the way leaves nothing behind). A device, FIFO or open descriptor target is written
/// straight into instead (what was written stays written). write_file_atomically is this class
/// used once.
class AtomicOutputFile {
 public:
  /// Checks `path` as check_can_write does, creates the target's missing parent directories,
  /// removes the abandoned temporary files of the target beside it, and opens and locks the
  /// temporary file (or opens the device, FIFO or descriptor itself; opening a FIFO waits for
  /// its reader). Throws Error when that fails.
  AtomicOutputFile(std::filesystem::path path, bool overwrite);
  ~AtomicOutputFile();
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;

  /// Appends `bytes`. Throws Error naming the file when the write fails (e.g. disk full, or
  /// "File too large" beyond `ulimit -f`).
  void write(std::string_view bytes);
  /// Regular target: flushes to disk and renames over the target (without `overwrite`, by a
  /// rename that fails when a file appeared there meanwhile: "exists; use --force"). Direct
  /// target: closes it. Throws Error on failure; the temporary file is removed.
  void commit();

 private:
  std::filesystem::path path_;       ///< as the user gave it (named in messages)
  std::filesystem::path target_;     ///< where the bytes go: path_ with its links followed
  std::filesystem::path temporary_;  ///< empty when writing straight into target_
  bool overwrite_ = false;
  int fd_ = -1;
  int pending_slot_ = -1;  ///< slot in the interrupt clean-up table, -1 if not tracked
  bool committed_ = false;
};

}  // namespace sigmatau
