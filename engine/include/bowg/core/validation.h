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

void requireFiniteAtLeast(const std::string& name, double v, double lo);
void requireFinitePositive(const std::string& name, double v);
void requireUnitInterval(const std::string& name, double v);  ///< [0, 1]
void requireIntAtLeast(const std::string& name, int v, int lo);
void requireIntInRange(const std::string& name, int v, int lo, int hi);  ///< [lo, hi]

}  // namespace check
}  // namespace bowg
