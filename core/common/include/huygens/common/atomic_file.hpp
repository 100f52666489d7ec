#pragma once
// Checked, atomic, durable file output: a file is written to PATH.tmp beside its target, every
// write and the close are checked, the data are flushed to the disk (fsync) and only then is the
// complete file renamed onto PATH, and the rename itself is flushed (fsync of the folder). A failed
// write removes the temporary and leaves the previous PATH as it was; a crash of the process or of
// the machine leaves either the previous PATH or the new one, whole (docs/robustness.md). A PATH that
// is a device or a pipe (/dev/stdout, /dev/full, a FIFO) is written in place; a symbolic link is
// followed.
#include <cstddef>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

namespace huygens {

/// An output file could not be written; what() names the file and the system's reason.
class IoError : public std::runtime_error {
 public:
  IoError(const std::string& path, const std::string& reason);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

/// Whether a commit waits for the disk: `to_disk` (fsync of the file before the rename and of its
/// folder after it; survives a power cut), `file` (the file's fsync only: the caller flushes the
/// folder once for several files, sync_folder(), before it lists them) or `cache` (the rename
/// alone; survives a crash of the process, not of the machine; `huygens run --no-fsync`).
enum class Sync { to_disk, file, cache };

/// One file written atomically: write() any number of times, then commit(). Destroyed without
/// commit() (an exception, a stop), it removes its temporary and PATH is untouched.
class AtomicFile {
 public:
  explicit AtomicFile(std::string path, Sync sync = Sync::to_disk);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// Appends bytes; throws IoError (disk full, file too large, I/O error) naming PATH.
  void write(std::span<const std::byte> bytes);
  void write(std::string_view text) { write(std::as_bytes(std::span(text.data(), text.size()))); }
  /// Flushes (Sync::to_disk, Sync::file), closes (checked), renames the temporary onto PATH and
  /// flushes the folder (Sync::to_disk). Throws IoError naming PATH when any of these fails.
  void commit();

 private:
  std::string path_, target_, tmp_;  // target_: PATH with its symbolic links resolved
  int fd_ = -1;
  Sync sync_;
};

/// Writes `text` to `path` atomically (AtomicFile).
void write_file_atomic(const std::string& path, std::string_view text, Sync sync = Sync::to_disk);

/// Flushes the folder `dir` (its entries: a rename or a new file in it) to the disk; IoError
/// naming `what` when the file system reports a failure.
void sync_folder(const std::string& dir, const std::string& what);

/// Checks before a run that `path` can be written at its end: its folder exists and takes a new
/// file, and `path` is not a folder. Throws IoError with the reason.
void check_output_file(const std::string& path);

}  // namespace huygens
