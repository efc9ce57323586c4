// The checks every stage's options validate() is written with. Each throws
// InvalidParameter("<name> <why> (got <value>)"), where name is the field as
// the user sets it ("similarity.lambda_1", "features.orb_levels"), so that a
// message leads to the launch-file or dynamic-reconfigure parameter without
// reading the code. Comparisons are written so that NaN fails them
// (!(x >= lo) instead of x < lo).
#pragma once

#include <sstream>
#include <string>

namespace bowg {
namespace check {

/// The value as the message shows it.
template <typename T>
std::string str(T v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

[[noreturn]] void fail(const std::string& name, const std::string& why, const std::string& got);

// The names are C strings: options are validated where they are used too
// (once per scored candidate in the temporal score), and a std::string
// argument would be built, and allocated, on every call, not only on failure.
void requireFiniteAtLeast(const char* name, double v, double lo);
void requireFinitePositive(const char* name, double v);
void requireUnitInterval(const char* name, double v);  ///< [0, 1]
void requireIntAtLeast(const char* name, int v, int lo);
void requireIntInRange(const char* name, int v, int lo, int hi);  ///< [lo, hi]

}  // namespace check
}  // namespace bowg
