// The start-up failures of the nodelets of this process (startup_status.h).
#include "bowg_ros/startup_status.h"

#include <map>
#include <mutex>

namespace bowg_ros {
namespace {

std::mutex& failuresMutex() {
  static std::mutex m;
  return m;
}

std::map<std::string, std::string>& failures() {
  static std::map<std::string, std::string> f;
  return f;
}

}  // namespace

void reportStartupFailure(const std::string& nodelet, const std::string& why) {
  std::lock_guard<std::mutex> lock(failuresMutex());
  failures()[nodelet] = why;
}

bool startupFailed(const std::string& nodelet, std::string* why) {
  std::lock_guard<std::mutex> lock(failuresMutex());
  const auto it = failures().find(nodelet);
  if (it == failures().end()) return false;
  if (why) *why = it->second;
  return true;
}

}  // namespace bowg_ros
