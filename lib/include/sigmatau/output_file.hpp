#pragma once
/// \file output_file.hpp
/// Nothing lost: every output file is written to a temporary name in its directory and renamed
/// into place, and an existing file is only replaced when the user said --force.

#include <filesystem>
#include <string_view>

namespace sigmatau {

/// Writes `content` to `path` atomically: creates missing parent directories, writes
/// "<path>.tmp-<random>" in the same directory, flushes it to disk and renames it over `path`.
/// Throws Error (and leaves no temporary file behind) when `path` exists and `overwrite` is
/// false ("... exists; use --force to overwrite"), or when the directory cannot be created or
/// written, or the disk is full.
void write_file_atomically(const std::filesystem::path& path, std::string_view content,
                           bool overwrite);

/// Throws the same "exists" Error as write_file_atomically, early, before long work starts; and
/// check_can_create_in's Error when the file could not be created there.
void check_can_write(const std::filesystem::path& path, bool overwrite);

/// Throws Error when nothing could be created at `path`: its nearest existing ancestor D is not
/// writable and searchable ("cannot write PATH: <reason> (directory D)") or is not a directory
/// ("cannot create directory D: Not a directory"). Missing directories in between are fine
/// (they are created). Called early, so that a run does not fail only after its long work.
void check_can_create_in(const std::filesystem::path& path);

/// Unlinks the temporary file of every AtomicOutputFile that is open and not yet committed, and
/// the scratch paths an InterruptCleanup tracks, and nothing else (the outputs themselves are
/// never touched). Uses only async-signal-safe calls, so a SIGINT / SIGTERM handler can call it
/// before the process dies: an interrupted run then leaves neither its output nor a partial
/// "<path>.tmp-<random>" behind. A temporary name longer
/// than 4095 bytes, or more than 32 open at once, is not tracked (it is still removed on the
/// ordinary paths: commit, exception, destructor).
void remove_pending_temporaries() noexcept;

/// Puts a scratch file or directory of the run (not an output) on the same interrupt clean-up
/// table for as long as this object lives: remove_pending_temporaries() unlinks tracked files,
/// then removes tracked directories that are empty by then. The owner still removes the path
/// on the ordinary paths; this only covers a signal. Untracked silently when the table is full.
class InterruptCleanup {
 public:
  explicit InterruptCleanup(const std::filesystem::path& path);
  ~InterruptCleanup();
  InterruptCleanup(const InterruptCleanup&) = delete;
  InterruptCleanup& operator=(const InterruptCleanup&) = delete;

 private:
  int slot_ = -1;
};

/// A file written piece by piece (too large to hold as one string) that appears at `path` only
/// when commit() succeeds: it is written to "<path>.tmp-<random>" in the same directory, and the
/// temporary file is removed if the object is destroyed before commit() (an exception on the
/// way leaves nothing behind). write_file_atomically is this class used once.
class AtomicOutputFile {
 public:
  /// Checks `path` as check_can_write does, creates missing parent directories and opens the
  /// temporary file. Throws Error when any of that fails.
  AtomicOutputFile(std::filesystem::path path, bool overwrite);
  ~AtomicOutputFile();
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;

  /// Appends `bytes`. Throws Error naming the file when the write fails (e.g. disk full).
  void write(std::string_view bytes);
  /// Flushes to disk and renames over `path` (re-checking first that no file appeared there
  /// meanwhile unless overwriting). Throws Error on failure; the temporary file is removed.
  void commit();

 private:
  std::filesystem::path path_;
  std::filesystem::path temporary_;
  bool overwrite_ = false;
  int fd_ = -1;
  int pending_slot_ = -1;  ///< slot in the interrupt clean-up table, -1 if not tracked
  bool committed_ = false;
};

}  // namespace sigmatau
