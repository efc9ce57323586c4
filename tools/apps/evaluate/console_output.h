// What bowg_evaluate prints while it works: a progress bar on stderr and
// printf-style number formatting for the summary.
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>
#include <utility>

namespace bowg {
namespace evaluate_app {

class ProgressBar {
 public:
  ProgressBar(std::string label, bool quiet) : label_(std::move(label)), quiet_(quiet) {}
  void operator()(std::size_t done, std::size_t total) {
    if (quiet_ || total == 0) return;
    const int percent = static_cast<int>(100 * done / total);
    if (percent == last_ && done != total) return;
    last_ = percent;
    const int width = 30, filled = width * percent / 100;
    std::fprintf(stderr, "\r%-22s [%s%s] %3d%% %zu/%zu", label_.c_str(),
                 std::string(filled, '#').c_str(), std::string(width - filled, '.').c_str(),
                 percent, done, total);
    if (done == total) std::fprintf(stderr, "\n");
  }

 private:
  std::string label_;
  bool quiet_;
  int last_ = -1;
};

inline std::string fmt(const char* format, double a, double b = 0, double c = 0, double d = 0) {
  char buf[256];
  std::snprintf(buf, sizeof(buf), format, a, b, c, d);
  return buf;
}

}  // namespace evaluate_app
}  // namespace bowg
