#pragma once
// Checked, atomic file output: a file is written to PATH.tmp beside its target, every write and
// the close are checked, and only a complete file is renamed onto PATH. A failed write removes
// the temporary and leaves the previous PATH as it was (docs/robustness.md). A PATH that is a device
// or a pipe (/dev/stdout, /dev/full, a FIFO) is written in place; a symbolic link is followed.
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

/// One file written atomically: write() any number of times, then commit(). Destroyed without
/// commit() (an exception, a stop), it removes its temporary and PATH is untouched.
class AtomicFile {
 public:
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// Appends bytes; throws IoError (disk full, file too large, I/O error) naming PATH.
  void write(std::span<const std::byte> bytes);
  void write(std::string_view text) { write(std::as_bytes(std::span(text.data(), text.size()))); }
  /// Closes (checked) and renames the temporary onto PATH.
  void commit();

 private:
  std::string path_, target_, tmp_;  // target_: PATH with its symbolic links resolved
  int fd_ = -1;
};

/// Writes `text` to `path` atomically (AtomicFile).
void write_file_atomic(const std::string& path, std::string_view text);

/// Checks before a run that `path` can be written at its end: its folder exists and takes a new
/// file, and `path` is not a folder. Throws IoError with the reason.
void check_output_file(const std::string& path);

}  // namespace huygens
