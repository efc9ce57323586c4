#include "bowg/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "bowg/errors.h"

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

}  // namespace

AtomicFileWriter::AtomicFileWriter(const std::string& path) : path_(path) {
  if (path.empty()) throw IoError("cannot write a file with an empty path");
  const std::string base = baseNameOf(path);
  if (base.empty() || base == "." || base == "..") {
    throw IoError("cannot write '" + path + "': the path names a directory");
  }
  std::string dir = directoryOf(path);
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

void writeFileAtomically(const std::string& path, const void* data, std::size_t size) {
  AtomicFileWriter writer(path);
  const int fd = ::open(writer.tempPath().c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    throw IoError("cannot create '" + writer.tempPath() + "' (to write '" + path +
                  "'): " + systemError());
  }
  const char* p = static_cast<const char*>(data);
  std::size_t left = size;
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      const std::string err = systemError();
      ::close(fd);
      throw IoError("cannot write '" + path + "': " + err);
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) {
    const std::string err = systemError();
    ::close(fd);
    throw IoError("cannot sync '" + path + "': " + err);
  }
  if (::close(fd) != 0) throw IoError("cannot close '" + path + "': " + systemError());
  writer.commit();
}

}  // namespace bowg
