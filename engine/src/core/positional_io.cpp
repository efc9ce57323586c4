#include "core/positional_io.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "bowg/core/errors.h"

namespace bowg {

std::size_t preadUpTo(int fd, void* dst, std::size_t n, std::uint64_t offset,
                      const std::string& what) {
  char* out = static_cast<char*>(dst);
  std::size_t done = 0;
  while (done < n) {
    const ssize_t got = ::pread(fd, out + done, n - done, static_cast<off_t>(offset + done));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw IoError(what + ": " + std::strerror(errno));
    if (got == 0) break;
    done += static_cast<std::size_t>(got);
  }
  return done;
}

void pwriteAll(int fd, const void* src, std::size_t n, std::uint64_t offset,
               const std::string& what) {
  const char* p = static_cast<const char*>(src);
  for (std::size_t done = 0; done < n;) {
    const ssize_t got = ::pwrite(fd, p + done, n - done, static_cast<off_t>(offset + done));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw IoError(what + ": " + std::strerror(errno));
    done += static_cast<std::size_t>(got);
  }
}

}  // namespace bowg
