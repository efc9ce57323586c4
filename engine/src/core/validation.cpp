#include "bowg/core/validation.h"

#include <cmath>

#include "bowg/core/errors.h"

namespace bowg {
namespace check {

void fail(const std::string& name, const std::string& why, const std::string& got) {
  throw InvalidParameter(name + " " + why + " (got " + got + ")");
}

void requireFiniteAtLeast(const char* name, double v, double lo) {
  if (!std::isfinite(v) || !(v >= lo)) fail(name, "must be a finite number >= " + str(lo), str(v));
}

void requireFinitePositive(const char* name, double v) {
  if (!std::isfinite(v) || !(v > 0.0)) fail(name, "must be a finite number > 0", str(v));
}

void requireUnitInterval(const char* name, double v) {
  if (!(v >= 0.0 && v <= 1.0)) fail(name, "must be in [0, 1]", str(v));
}

void requireIntAtLeast(const char* name, int v, int lo) {
  if (v < lo) fail(name, "must be >= " + str(lo), str(v));
}

void requireIntInRange(const char* name, int v, int lo, int hi) {
  if (v < lo || v > hi) fail(name, "must be in [" + str(lo) + ", " + str(hi) + "]", str(v));
}

}  // namespace check
}  // namespace bowg
