#include "bowg/core/errors.h"

#include <cstdio>

namespace bowg {

std::string formatNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

}  // namespace bowg
