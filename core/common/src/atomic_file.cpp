#include "huygens/common/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace huygens {

IoError::IoError(const std::string& path, const std::string& reason)
    : std::runtime_error("cannot write " + path + ": " + reason), path_(path) {}

AtomicFile::AtomicFile(std::string path, Sync sync) : path_(std::move(path)), sync_(sync) {
  struct stat st {};
  if (::stat(path_.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode)) {
    // a device, pipe or socket (/dev/null, /dev/stdout, a FIFO) is written in place: a rename would
    // replace the node by a regular file. O_NONBLOCK only for the open: a FIFO without a reader
    // fails with ENXIO instead of waiting for one.
    fd_ = ::open(path_.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC | O_NONBLOCK);
    if (fd_ < 0) throw IoError(path_, std::strerror(errno));
    ::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) & ~O_NONBLOCK);
    return;  // no temporary: commit() only closes
  }
  // through a symbolic link: the temporary goes beside the file it names and the rename replaces
  // that file, so the link stays (a missing or dangling target: beside PATH)
  std::error_code ec;
  const std::filesystem::path real = std::filesystem::canonical(path_, ec);
  target_ = ec ? path_ : real.string();
  tmp_ = target_ + ".tmp";
  fd_ = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw IoError(path_, std::strerror(errno));
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!tmp_.empty()) ::unlink(tmp_.c_str());  // not committed: PATH keeps its previous content
}

void AtomicFile::write(std::span<const std::byte> bytes) {
  const char* p = reinterpret_cast<const char*>(bytes.data());
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw IoError(path_, n < 0 ? std::strerror(errno) : "no progress");
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

// The order that makes a renamed file whole after a power cut: the data reach the disk (fsync)
// before the rename makes them visible under PATH, and the folder's entry is flushed after it, so
// a caller that lists PATH (meta.json) lists a file that is on the disk.
void AtomicFile::commit() {
  const int fd = fd_;
  fd_ = -1;
  const bool durable = sync_ != Sync::cache && !tmp_.empty();  // a device or a pipe: no fsync
  if (durable && ::fsync(fd) != 0) {
    const int err = errno;
    ::close(fd);
    throw IoError(path_, std::string("fsync: ") + std::strerror(err));
  }
  if (::close(fd) != 0) throw IoError(path_, std::strerror(errno));  // delayed write errors (NFS)
  if (tmp_.empty()) return;                                          // written in place (a device or a pipe)
  if (std::rename(tmp_.c_str(), target_.c_str()) != 0) throw IoError(path_, std::strerror(errno));
  tmp_.clear();
  if (durable && sync_ == Sync::to_disk) sync_folder(std::filesystem::path(target_).parent_path().string(), path_);
}

void write_file_atomic(const std::string& path, std::string_view text, Sync sync) {
  AtomicFile f(path, sync);
  f.write(text);
  f.commit();
}

void sync_folder(const std::string& dir, const std::string& what) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) throw IoError(what, std::string("cannot open its folder to flush it: ") + std::strerror(errno));
  const int rc = ::fsync(fd), err = errno;
  ::close(fd);
  // a file system that cannot flush a folder (EINVAL) has nothing pending in it
  if (rc != 0 && err != EINVAL) throw IoError(what, std::string("fsync of its folder: ") + std::strerror(err));
}

void check_output_file(const std::string& path) {
  namespace fs = std::filesystem;
  if (path.empty()) throw IoError("\"\"", "an empty file name");
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw IoError(path, "it is a folder");
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    // a device or a pipe: opened only for the real write (opening and closing a FIFO here would
    // end its reader's input before the run)
    if (::access(path.c_str(), W_OK) != 0) throw IoError(path, std::strerror(errno));
    return;
  }
  // the real test: the temporary the write will use can be created (folder exists, writable,
  // file system not read-only), then it is removed again
  AtomicFile probe(path);
}

}  // namespace huygens
