#include "bowg/core/errors.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace bowg {

std::string formatNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

std::string errnoReason() { return std::strerror(errno); }

}  // namespace bowg
