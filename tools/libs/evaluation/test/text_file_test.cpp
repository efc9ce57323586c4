// The tools' text inputs (ground truth, odometry, odometry positions,
// intrinsics, loop and trajectory CSVs, all read by readTextFile): a FIFO, a
// directory, a device or a huge sparse file is refused within 1 s and
// 100 MB, the message naming the file, what it is for and the reason.
#include "bowg_evaluation/text_file.h"

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "bowg/core/errors.h"
#include "bowg_evaluation/ground_truth.h"
#include "bowg_evaluation/intrinsics_file.h"
#include "bowg_evaluation/odometry_file.h"
#include "core/special_files.h"

namespace bowg {
namespace eval {
namespace {

struct Reader {
  const char* name;
  std::function<void(const std::string&)> read;
};

TEST(TextFile, SpecialFilesAreRefusedByEveryReader) {
  const Reader readers[] = {
      {"loop", [](const std::string& p) { readTextFile(p, "loop"); }},
      {"ground-truth", [](const std::string& p) { readGroundTruth(p); }},
      {"odometry", [](const std::string& p) { readOdometry(p); }},
      {"odometry positions", [](const std::string& p) { readOdometryPoses(p); }},
      {"intrinsics", [](const std::string& p) { readIntrinsics(p); }},
  };
  const auto files = testing::makeSpecialFiles(std::string(BOWG_TEST_OUTPUT_DIR) + "/text_file",
                                               ".csv", 3ull << 30, "more than the limit");
  for (const Reader& r : readers) {
    SCOPED_TRACE(r.name);
    for (const testing::SpecialFile& f : files) {
      SCOPED_TRACE(f.what);
      testing::expectRefusedFast(f.path, f.reason, r.read);
      testing::expectRefusedFast(f.path, std::string("the ") + r.name + " file", r.read);
    }
  }
  testing::expectSpecialFilesRefused(files, readers[0].read);  // and cleans up
}

TEST(TextFile, AMissingFileSaysWhy) {
  const std::string path = std::string(BOWG_TEST_OUTPUT_DIR) + "/no_such_truth.csv";
  testing::expectRefusedFast(
      path, "cannot open the ground-truth file '" + path + "': No such file or directory",
      [](const std::string& p) { readGroundTruth(p); });
}

}  // namespace
}  // namespace eval
}  // namespace bowg
