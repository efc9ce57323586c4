// Helpers of the tests that drive the command-line tools: run a shell
// command with its output in a log file, read and write a whole file.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

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

/// Writes `text` as the whole of `path`.
inline void writeAll(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

}  // namespace tool_test
}  // namespace bowg
