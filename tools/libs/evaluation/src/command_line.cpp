// Numbers from the tools' command lines (command_line.h).
#include "bowg_evaluation/command_line.h"

#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace bowg {
namespace eval {

double numberArgument(const std::string& flag, const std::string& value) {
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || !std::isfinite(v)) {
    throw std::invalid_argument(flag + ": '" + value + "' is not a number");
  }
  return v;
}

}  // namespace eval
}  // namespace bowg
