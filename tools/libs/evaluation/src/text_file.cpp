#include "bowg_evaluation/text_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "bowg/core/errors.h"

namespace bowg {
namespace eval {

std::string readTextFile(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw IoError("cannot read the " + what + " file " + path + ": " + std::strerror(errno));
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace eval
}  // namespace bowg
