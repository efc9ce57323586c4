// Helpers of the tests that drive the command-line tools: run a shell
// command with its output in a log file, read and write a whole file, read
// a CSV file's cells.
#pragma once

#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

namespace bowg {
namespace tool_test {

/// Runs `command` through the shell with stdout and stderr in `log`; returns
/// its exit code, -1 when it did not exit normally.
inline int run(const std::string& command, const std::string& log = "/dev/null") {
  const int status = std::system((command + " > " + log + " 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// The whole file, empty when it cannot be read.
inline std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

using Table = std::vector<std::vector<std::string>>;

/// The rows of a CSV file (header included), each split at the commas; empty
/// when it cannot be read.
inline Table readCsv(const std::string& path) {
  Table rows;
  std::istringstream lines(readAll(path));
  std::string line;
  while (std::getline(lines, line)) {
    std::vector<std::string> fields;
    std::istringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) fields.push_back(cell);
    rows.push_back(fields);
  }
  return rows;
}

/// Writes `text` as the whole of `path`.
inline void writeAll(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

/// A TCP port nobody listens on now (the kernel's pick), for a master of a
/// test's own: a concurrent roscore or rostest elsewhere is never disturbed.
/// -1 when none can be found.
inline int freePort() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = 0;
  socklen_t len = sizeof(addr);
  if (fd < 0 || ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0) {
    if (fd >= 0) ::close(fd);
    return -1;
  }
  const int port = ntohs(addr.sin_port);
  ::close(fd);
  return port;
}

}  // namespace tool_test
}  // namespace bowg
