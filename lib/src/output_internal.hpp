#pragma once
// Private to the library's output writers (output_file.cpp, output_directory.cpp,
// output_inputs.cpp, output_leftovers.cpp, scratch_dir.hpp): what an output path names, the
// inputs no output may replace, and the locks that tell an abandoned temporary name from a
// live one. Not installed.

#include <sys/types.h>

#include <filesystem>
#include <string>
#include <string_view>

namespace sigmatau::detail {

/// What an output path names, after following the symbolic links of its last component.
enum class TargetKind {
  absent,          // nothing there yet (or unreachable: the directory checks report why)
  regular,         // a regular file: replaced atomically with --force
  directory,       // refused for a file; for a report directory, see output_directory.cpp
  device_or_pipe,  // a character device or FIFO (or another process's descriptor): opened
  descriptor,      // one of this process's open descriptors (/dev/stdout, /dev/fd/N): dup'ed
  socket,          // refused: open(2) cannot write one
  block_device,    // refused: a disk is never an output
};

struct Target {
  std::filesystem::path path;  // the path with the links of its last component followed
  TargetKind kind = TargetKind::absent;
  int descriptor = -1;  // for TargetKind::descriptor
};

/// Follows the symbolic links of `requested`'s last component (at most 40, Linux's own limit)
/// and says what is there. Throws Error on a loop.
Target resolve_target(const std::filesystem::path& requested);

/// "PATH" or, when links led elsewhere, "PATH (-> TARGET)", for messages.
std::string describe(const std::filesystem::path& requested, const Target& target);

/// The directory `path` is in ("." for a bare name).
std::filesystem::path directory_of(const std::filesystem::path& path);

/// "a/b/" names "a/b" (shell completion types directories with the slash).
std::filesystem::path without_trailing_separator(std::filesystem::path path);

/// check_can_create_in naming `shown` (the path as the user gave it, with where its links led).
void check_can_create_in(const std::filesystem::path& path, const std::string& shown);

/// Throws Error when `target` is an input of this run (note_input), or, for a directory, holds
/// one: "cannot write PATH: it is an input of this run ..." / "... it holds INPUT, an input of
/// this run ...". Nothing is thrown for an absent target.
void refuse_input_target(const std::filesystem::path& requested, const Target& target);

/// renameat2(RENAME_NOREPLACE): moves `from` to `to` only if `to` does not exist, atomically.
/// Returns 0 or the errno (EEXIST when `to` exists). On a file system without it, link(2) (a
/// file) or, last, a check then rename(2) (a directory on such a file system: not atomic).
int rename_without_replacing(const std::filesystem::path& from, const std::filesystem::path& to);

/// Takes an exclusive flock(2) on `fd`, the file or directory just created at `path`, and keeps
/// it while `fd` is open (the lock dies with the process, also of kill -9): the mark of a live
/// writer. Returns false when `path` no longer names what `fd` holds (remove_abandoned_leftovers
/// took it between its creation and the lock): make another. On a file system without locks,
/// true with no lock: such leftovers are then never taken as abandoned.
bool lock_as_live(int fd, const std::filesystem::path& path);

/// The interrupt clean-up table (remove_pending_temporaries): puts `path` on it and returns its
/// slot, or -1 when the name is too long or the table is full (then not tracked).
int track_pending_path(const std::filesystem::path& path);
/// Takes a slot of track_pending_path off the table (-1: nothing).
void untrack_pending_path(int slot);

/// Whether `name` is a temporary name this library gives beside an output called `base`:
/// "<base>.tmp-XXXXXX" (six hex digits, AtomicOutputFile) or "<base>.partial-XXXXXX" (six
/// letters or digits, mkdtemp; ".old" after it from versions before RENAME_EXCHANGE).
bool is_leftover_name(std::string_view name, std::string_view base);

/// Removes, from `directory`, every leftover of `base` (is_leftover_name) that no live writer
/// holds: its lock can be taken, so the process that made it is gone (kill -9, a power cut).
/// A live run's temporary files are locked and kept. Errors are ignored: leftovers are only
/// tidied.
void remove_abandoned_leftovers(const std::filesystem::path& directory, std::string_view base);

/// A test hook: when the environment variable SIGMATAU_TEST_HOLD_COMMIT holds "NAME:FILE", an
/// output whose last path component is NAME waits, just before it is claimed by its rename, until
/// FILE exists (at most 60 s), so that the tests can start a second run, or kill this one, while
/// it holds its temporary name (a race that happens by chance a few times in a hundred
/// otherwise). Does nothing without the variable or for another name.
void hold_commit_for_tests(const std::filesystem::path& target);

}  // namespace sigmatau::detail
