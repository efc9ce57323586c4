#include "bowg/core/atomic_file.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "bowg/core/errors.h"
#include "core/positional_io.h"

namespace bowg {
namespace {

std::string systemError() { return std::strerror(errno); }

std::string directoryOf(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

std::string baseNameOf(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// Unique per process and call, so that concurrent writers (threads or
// processes) of the same destination never share a temporary file.
std::string uniqueTag() {
  static std::atomic<unsigned> counter{0};
  return std::to_string(static_cast<long>(::getpid())) + "-" + std::to_string(counter++);
}

void fsyncPath(const std::string& path, int flags, const std::string& what) {
  const int fd = ::open(path.c_str(), flags);
  if (fd < 0) throw IoError("cannot open " + what + " '" + path + "' to sync it: " + systemError());
  const int rc = ::fsync(fd);
  const std::string err = rc != 0 ? systemError() : std::string();
  ::close(fd);
  if (rc != 0) throw IoError("cannot sync " + what + " '" + path + "': " + err);
}

// "<pid>" when `name` is ".tmp-<pid>-<n>-<base>" (the writer's naming,
// uniqueTag()), else 0.
long writerPidOf(const std::string& name, const std::string& base) {
  const std::string suffix = "-" + base;
  if (name.compare(0, 5, ".tmp-") != 0 || name.size() <= 5 + suffix.size() ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) {
    return 0;
  }
  // "<pid>-<n>" between the prefix and the suffix.
  const std::string tag = name.substr(5, name.size() - 5 - suffix.size());
  const std::size_t dash = tag.find('-');
  if (dash == 0 || dash == std::string::npos || dash > 9 ||
      tag.find_first_not_of("0123456789", 0) != dash ||
      tag.find_first_not_of("0123456789", dash + 1) != std::string::npos ||
      dash + 1 == tag.size()) {
    return 0;
  }
  return std::strtol(tag.substr(0, dash).c_str(), nullptr, 10);
}

// A temporary is removed only when everything says this program's writer made
// it: the writer's naming for this destination, a dead writer (a live pid,
// even a reused one, keeps it), a regular file (not a link, directory or
// FIFO someone gave that name) owned by our user. Its content is not
// checked: a save killed early leaves an empty or short file, shorter than
// any magic, and the YAML and gzip writers have no magic of their own.
std::size_t removeStaleTemporaries(const std::string& dir, const std::string& base) {
  DIR* d = ::opendir(dir.c_str());
  if (d == nullptr) return 0;  // the write itself will report the directory
  std::size_t removed = 0;
  while (const dirent* e = ::readdir(d)) {
    const std::string name = e->d_name;
    const long pid = writerPidOf(name, base);
    if (pid <= 0 || ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
    struct stat st;
    if (::fstatat(::dirfd(d), name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0 ||
        !S_ISREG(st.st_mode) || st.st_uid != ::geteuid()) {
      continue;
    }
    if (::unlinkat(::dirfd(d), name.c_str(), 0) == 0) ++removed;
  }
  ::closedir(d);
  return removed;
}

}  // namespace

AtomicFileWriter::AtomicFileWriter(const std::string& path) : path_(path) {
  if (path.empty()) throw IoError("cannot write a file with an empty path");
  const std::string base = baseNameOf(path);
  if (base.empty() || base == "." || base == "..") {
    throw IoError("cannot write '" + path + "': the path names a directory");
  }
  std::string dir = directoryOf(path);
  removeStaleTemporaries(dir, base);
  temp_path_ = (dir == "/" ? std::string("/") : dir + "/") + ".tmp-" + uniqueTag() + "-" + base;
}

AtomicFileWriter::~AtomicFileWriter() {
  if (!committed_) std::remove(temp_path_.c_str());
}

void AtomicFileWriter::commit() {
  if (committed_) return;
  try {
    fsyncPath(temp_path_, O_RDONLY, "temporary file");
    if (std::rename(temp_path_.c_str(), path_.c_str()) != 0) {
      throw IoError("cannot rename '" + temp_path_ + "' to '" + path_ + "': " + systemError());
    }
  } catch (...) {
    std::remove(temp_path_.c_str());
    throw;
  }
  committed_ = true;
  // The rename is durable only once the directory entry is on disk. Some
  // file systems refuse to fsync a directory: the data is safe either way.
  try {
    fsyncPath(directoryOf(path_), O_RDONLY | O_DIRECTORY, "directory");
  } catch (const IoError&) {
  }
}

AtomicFileStream::AtomicFileStream(const std::string& path) : writer_(path) {
  fd_ = ::open(writer_.tempPath().c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    throw IoError("cannot create '" + writer_.tempPath() + "' (to write '" + path +
                  "'): " + systemError());
  }
}

AtomicFileStream::~AtomicFileStream() {
  if (fd_ >= 0) ::close(fd_);
}

void AtomicFileStream::write(const void* data, std::size_t n) { writeAt(data, n, size_); }

void AtomicFileStream::writeAt(const void* data, std::size_t n, std::uint64_t offset) {
  pwriteAll(fd_, data, n, offset, "cannot write '" + path() + "'");
  size_ = std::max<std::uint64_t>(size_, offset + n);
}

void AtomicFileStream::readAt(void* data, std::size_t n, std::uint64_t offset) const {
  const std::string what = "cannot read back '" + path() + "' while writing it";
  if (preadUpTo(fd_, data, n, offset, what) < n) throw IoError(what + ": it ends early");
}

void AtomicFileStream::commit() {
  if (::fsync(fd_) != 0) throw IoError("cannot sync '" + path() + "': " + systemError());
  const int rc = ::close(fd_);
  fd_ = -1;
  if (rc != 0) throw IoError("cannot close '" + path() + "': " + systemError());
  writer_.commit();
}

void writeFileAtomically(const std::string& path, const void* data, std::size_t size) {
  AtomicFileStream out(path);
  out.write(data, size);
  out.commit();
}

std::size_t removeStaleTemporariesOf(const std::string& path) {
  const std::string base = baseNameOf(path);
  if (path.empty() || base.empty() || base == "." || base == "..") return 0;
  return removeStaleTemporaries(directoryOf(path), base);
}

}  // namespace bowg
