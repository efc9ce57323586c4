// bowg_train_vocabulary's progress bar (progress_bar.h).
#include "progress_bar.h"

#include <cstddef>
#include <cstdio>
#include <string>

namespace bowg {
namespace train_vocabulary_app {

// Redraws only when the percentage or the stage changes, so that a log file
// gets ~100 lines, not one per image.
void progressBar(double fraction, const std::string& stage) {
  static int last_percent = -1;
  static std::string last_stage;
  const int percent = static_cast<int>(fraction * 100 + 0.5);
  if (percent == last_percent && stage == last_stage) return;
  last_percent = percent;
  last_stage = stage;
  const int width = 40;
  const int filled = static_cast<int>(fraction * width + 0.5);
  std::string bar(static_cast<std::size_t>(filled), '=');
  bar.resize(width, ' ');
  std::fprintf(stderr, "\r[%s] %3d%% %-40s", bar.c_str(), percent, stage.c_str());
  if (fraction >= 1.0) std::fprintf(stderr, "\n");
  std::fflush(stderr);
}

}  // namespace train_vocabulary_app
}  // namespace bowg
