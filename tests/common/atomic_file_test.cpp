// Checked atomic writes (atomic_file.hpp): a failed write leaves the previous file intact and no
// temporary behind. "Disk full" is made real with the file-size limit (RLIMIT_FSIZE), which makes
// write() fail with EFBIG exactly as a full disk makes it fail with ENOSPC.
#include "huygens/common/atomic_file.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

using namespace huygens;
namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::path(::testing::TempDir()) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// Lowers the soft file-size limit for its lifetime (SIGXFSZ ignored so write() returns EFBIG).
struct FileSizeLimit {
  rlimit old{};
  void (*old_handler)(int);
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &old);
    old_handler = std::signal(SIGXFSZ, SIG_IGN);
    rlimit lim = old;
    lim.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &lim);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &old);
    std::signal(SIGXFSZ, old_handler);
  }
};

}  // namespace

TEST(AtomicFile, WritesAndReplaces) {
  const fs::path d = fresh_dir("atomic_ok");
  write_file_atomic((d / "a.json").string(), "first\n");
  write_file_atomic((d / "a.json").string(), "second\n");
  EXPECT_EQ(slurp(d / "a.json"), "second\n");
  EXPECT_FALSE(fs::exists(d / "a.json.tmp"));
}

TEST(AtomicFile, FailedWriteKeepsThePreviousFile) {
  const fs::path d = fresh_dir("atomic_full");
  const std::string path = (d / "meta.json").string();
  write_file_atomic(path, "good\n");
  const std::string big(1 << 20, 'x');
  try {
    FileSizeLimit limit(4096);
    write_file_atomic(path, big);
    FAIL() << "a write past the file-size limit must throw";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("too large"), std::string::npos) << e.what();  // strerror(EFBIG)
  }
  EXPECT_EQ(slurp(path), "good\n");
  EXPECT_FALSE(fs::exists(path + ".tmp"));
}

TEST(AtomicFile, UncommittedFileLeavesNothing) {
  const fs::path d = fresh_dir("atomic_abandon");
  {
    AtomicFile f((d / "x.npy").string());
    f.write("partial");
  }
  EXPECT_TRUE(fs::is_empty(d));
}

TEST(AtomicFile, OutputTargetsAreCheckedBeforeARun) {
  const fs::path d = fresh_dir("atomic_check");
  EXPECT_NO_THROW(check_output_file((d / "stats.json").string()));
  EXPECT_TRUE(fs::is_empty(d));  // the probe leaves nothing
  EXPECT_THROW(check_output_file((d / "missing" / "stats.json").string()), IoError);
  EXPECT_THROW(check_output_file(d.string()), IoError);  // a folder
  EXPECT_THROW(check_output_file(""), IoError);
}

// A target that is a device, a pipe or a symbolic link is written through, not replaced: renaming a
// temporary onto it turned `--stats-json /dev/full` into a regular file (exit 0; run as root it
// replaced the device node) and a link into a copy.
TEST(AtomicFile, ADeviceAPipeOrALinkIsWrittenThroughNotReplaced) {
  const fs::path d = fresh_dir("atomic_special");
  fs::create_symlink("/dev/full", d / "full");
  try {
    write_file_atomic((d / "full").string(), "stats\n");
    FAIL() << "a write to /dev/full must fail";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("No space left"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_symlink(d / "full"));
  EXPECT_TRUE(fs::is_character_file("/dev/full"));

  write_file_atomic((d / "target.json").string(), "old\n");
  fs::create_symlink("target.json", d / "link.json");
  EXPECT_NO_THROW(check_output_file((d / "link.json").string()));
  write_file_atomic((d / "link.json").string(), "new\n");
  EXPECT_TRUE(fs::is_symlink(d / "link.json"));
  EXPECT_EQ(slurp(d / "target.json"), "new\n");
  EXPECT_FALSE(fs::exists(d / "target.json.tmp"));
  EXPECT_FALSE(fs::exists(d / "link.json.tmp"));

  // a FIFO (as bash's `>(cat)`): a write without a reader fails at once (not waiting), with one it
  // reaches the reader
  const fs::path fifo = d / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_THROW(write_file_atomic(fifo.string(), "abc"), IoError);
  const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  ASSERT_GE(reader, 0);
  EXPECT_NO_THROW(check_output_file(fifo.string()));
  write_file_atomic(fifo.string(), "abc");
  char buf[8] = {};
  EXPECT_EQ(::read(reader, buf, sizeof buf), 3);
  EXPECT_EQ(std::string(buf), "abc");
  ::close(reader);
  EXPECT_TRUE(fs::is_fifo(fifo));
}
