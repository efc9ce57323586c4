#include "bowg_evaluation/text_file.h"

#include "bowg/core/bounded_file.h"

namespace bowg {
namespace eval {

std::string readTextFile(const std::string& path, const std::string& what) {
  // A regular file within BOWG_MAX_TEXT_MB (bounded_file.h): a FIFO, a
  // device or a huge file is refused, naming the file and why, before a
  // byte is read.
  return readBoundedFile(path, FileKind::kText, "the " + what + " file");
}

}  // namespace eval
}  // namespace bowg
