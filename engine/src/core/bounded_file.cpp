#include "bowg/core/bounded_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <utility>

#include "bowg/core/errors.h"
#include "core/positional_io.h"

namespace bowg {
namespace {

constexpr std::uint64_t kMiB = 1ull << 20;

const char* limitVariable(FileKind kind) {
  switch (kind) {
    case FileKind::kVocabulary: return "BOWG_MAX_VOCABULARY_MB";
    case FileKind::kDatabase: return "BOWG_MAX_DATABASE_MB";
    case FileKind::kImage: return "BOWG_MAX_IMAGE_FILE_MB";
    case FileKind::kText: return "BOWG_MAX_TEXT_MB";
  }
  return "BOWG_MAX_TEXT_MB";
}

// What stat() says a non-regular file is, for the refusal.
std::string notRegularReason(mode_t mode) {
  if (S_ISDIR(mode)) return "it is a directory";
  if (S_ISFIFO(mode)) return "it is a FIFO (named pipe), not a regular file";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "it is a device, not a regular file";
  if (S_ISSOCK(mode)) return "it is a socket, not a regular file";
  return "it is not a regular file";
}

}  // namespace

std::uint64_t defaultFileLimit(FileKind kind) {
  switch (kind) {
    case FileKind::kVocabulary: return 1024 * kMiB;
    case FileKind::kDatabase: return 8192 * kMiB;
    case FileKind::kImage: return 256 * kMiB;
    case FileKind::kText: return 256 * kMiB;
  }
  return 256 * kMiB;
}

const char* fileKindName(FileKind kind) {
  switch (kind) {
    case FileKind::kVocabulary: return "vocabulary";
    case FileKind::kDatabase: return "database";
    case FileKind::kImage: return "image";
    case FileKind::kText: return "file";
  }
  return "file";
}

FileLimit fileLimit(FileKind kind) {
  FileLimit limit;
  limit.variable = limitVariable(kind);
  limit.max_bytes = defaultFileLimit(kind);
  const char* value = std::getenv(limit.variable.c_str());
  if (value == nullptr || *value == '\0') return limit;
  char* end = nullptr;
  errno = 0;
  const unsigned long long mb = std::strtoull(value, &end, 10);
  // Whole MiB up to 1 PiB: anything else is a typo, not a wish.
  if (errno != 0 || *end != '\0' || value[0] == '-' || mb == 0 || mb > (1ull << 30)) {
    throw InvalidParameter("environment variable " + limit.variable + "='" + value +
                           "' is not a whole number of MiB between 1 and 1073741824");
  }
  limit.max_bytes = static_cast<std::uint64_t>(mb) * kMiB;
  return limit;
}

std::string formatBytes(std::uint64_t bytes) {
  static const char* const units[] = {"kB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  if (bytes < 1024) return std::to_string(bytes) + (bytes == 1 ? " byte" : " bytes");
  double value = static_cast<double>(bytes) / 1024.0;
  int unit = 0;
  while (value >= 1024.0 && unit < 5) {
    value /= 1024.0;
    ++unit;
  }
  char text[32];
  std::snprintf(text, sizeof text, value < 10.0 ? "%.1f %s" : "%.0f %s", value, units[unit]);
  return text;
}

std::string limitMessage(FileKind kind, const std::string& path, const std::string& what_size,
                         const FileLimit& limit) {
  return limitMessage(std::string(fileKindName(kind)), path, what_size, limit);
}

std::string limitMessage(const std::string& label, const std::string& path,
                         const std::string& what_size, const FileLimit& limit) {
  return label + " '" + path + "' " + what_size +
         ", more than the limit of " + formatBytes(limit.max_bytes) +
         " (raise it with the environment variable " + limit.variable + ", in MiB)";
}

BoundedFile::BoundedFile(const std::string& path, FileKind kind, const std::string& label)
    : path_(path), kind_(kind), label_(label.empty() ? fileKindName(kind) : label) {
  const std::string name = label_ + " '" + path + "'";
  if (path.empty()) throw IoError("no " + label_ + " path given");
  // O_NONBLOCK: open() of a FIFO without a writer would wait for ever.
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd_ < 0) throw IoError("cannot open " + name + ": " + std::strerror(errno));
  struct stat st;
  if (::fstat(fd_, &st) != 0) {
    const std::string err = std::strerror(errno);
    ::close(fd_);
    throw IoError("cannot read " + name + ": " + err);
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd_);
    throw IoError("cannot read " + name + ": " + notRegularReason(st.st_mode));
  }
  size_ = static_cast<std::uint64_t>(st.st_size);
  const FileLimit limit = fileLimit(kind);
  if (size_ > limit.max_bytes) {
    ::close(fd_);
    throw IoError("cannot read " + limitMessage(label_, path, "is " + formatBytes(size_), limit));
  }
  // Regular files never block; blocking reads are the normal contract.
  ::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) & ~O_NONBLOCK);
}

BoundedFile::~BoundedFile() {
  if (fd_ >= 0) ::close(fd_);
}

BoundedFile::BoundedFile(BoundedFile&& other) noexcept
    : path_(std::move(other.path_)),
      kind_(other.kind_),
      label_(std::move(other.label_)),
      size_(other.size_),
      fd_(other.fd_) {
  other.fd_ = -1;
}

std::size_t BoundedFile::readSome(void* dst, std::size_t n) {
  while (true) {
    const ssize_t got = ::read(fd_, dst, n);
    if (got >= 0) return static_cast<std::size_t>(got);
    if (errno != EINTR) {
      throw IoError("cannot read " + label_ + " '" + path_ +
                    "': " + std::strerror(errno));
    }
  }
}

void BoundedFile::readExactly(void* dst, std::size_t n) {
  char* out = static_cast<char*>(dst);
  std::size_t done = 0;
  while (done < n) {
    const std::size_t got = readSome(out + done, n - done);
    if (got == 0) {
      throw IoError("cannot read " + label_ + " '" + path_ +
                    "': it ends after " + std::to_string(done) + " of " + std::to_string(n) +
                    " expected bytes");
    }
    done += got;
  }
}

std::string BoundedFile::readRest() {
  const off_t at = ::lseek(fd_, 0, SEEK_CUR);
  const std::uint64_t start = at > 0 ? static_cast<std::uint64_t>(at) : 0;
  std::string data(static_cast<std::size_t>(size_ > start ? size_ - start : 0), '\0');
  std::size_t done = 0;
  while (done < data.size()) {
    const std::size_t got = readSome(&data[done], data.size() - done);
    if (got == 0) break;  // shrank while we read: what is there is all there is
    done += got;
  }
  data.resize(done);
  return data;
}

void BoundedFile::readAt(void* dst, std::size_t n, std::uint64_t offset) const {
  const std::string what = "cannot read " + label_ + " '" + path_ + "'";
  if (preadUpTo(fd_, dst, n, offset, what) < n) {
    throw IoError(what + ": it ends before byte " + std::to_string(offset + n) +
                  " (shrunk since it was opened)");
  }
}

std::string readBoundedFile(const std::string& path, FileKind kind, const std::string& label) {
  BoundedFile file(path, kind, label);
  return file.readRest();
}

}  // namespace bowg
