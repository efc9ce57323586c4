// scripts/reinspection_suite.sh end to end on a short list of its own: a
// second survey of the same short circuit (the generator's --again), and a
// survey of another network against the first one's map (--save-map, --map;
// its odometer starts from 0 again), in two input modes; the table, the CSV
// and the per-half lines.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "shell_command.h"

namespace bowg {
namespace {

const std::string kDir = std::string(BOWG_TEST_OUTPUT_DIR) + "/reinspection_suite_test";

std::string env(const std::string& list, const std::string& extra = "") {
  return "BOWG_SKIP_DEPS=1 BOWG_SKIP_BUILD=1 BOWG_REINSPECTION_LIST=" + list +
         " BOWG_REINSPECTION_DIR=" + kDir + "/out BOWG_TOOLS_DIR=" + BOWG_TOOLS_BIN_DIR + " " +
         extra + " ";
}

TEST(ReinspectionSuite, RendersEvaluatesAndTabulatesAListOfPairs) {
  ASSERT_EQ(tool_test::run("rm -rf " + kDir + " && mkdir -p " + kDir), 0);
  const std::string list = kDir + "/list.txt";
  const std::string small = " --width 320 --height 240 --speed 1.0 --frames 60";
  {
    std::ofstream out(list);
    out << "# a comment, then two pairs\n"
        << "again_small | tuning | same | --seed 5 --route circuit --marks-per-metre 8 --again"
        << small << "\n\n"
        << "other_small | test | other | --seed 6 --route no-revisit --marks-per-metre 8" << small
        << " || --seed 106 --route no-revisit --marks-per-metre 8 --network-width 5" << small
        << "\n";
  }
  const std::string script = std::string(BOWG_REPO_DIR) + "/scripts/reinspection_suite.sh";
  const std::string log = kDir + "/suite.log";
  ASSERT_EQ(tool_test::run(env(list, "BOWG_REINSPECTION_MODES=positions,images") + script, log), 0)
      << tool_test::readAll(log);
  const std::string printed = tool_test::readAll(log);
  EXPECT_NE(printed.find("tuning positions cross-mission recall median"), std::string::npos)
      << printed;
  EXPECT_NE(printed.find("test   images    cross-mission recall - (no pair with positives)"),
            std::string::npos)
      << printed;
  const std::string csv = tool_test::readAll(kDir + "/out/reinspection.csv");
  EXPECT_EQ(csv.find("pair,half,kind,mode,cross_precision,cross_recall,cross_true_loops,"
                     "cross_false_loops,cross_positives,precision,recall,false_loops\n"),
            0u)
      << csv;
  // The second survey has places of the first (positives), and with the
  // odometry's positions finds them (60 frames are too few for images alone:
  // the verified chain takes its first queries); the other network has none,
  // and its run against the map continued its odometer from the map's.
  int tp = -1, fp = -1, positives = -1;
  const std::size_t same = csv.find("\nagain_small,tuning,same,positions,");
  ASSERT_NE(same, std::string::npos) << csv;
  ASSERT_EQ(
      std::sscanf(csv.c_str() + same, "\nagain_small,tuning,same,positions,%*[^,],%*[^,],%d,%d,%d",
                  &tp, &fp, &positives),
      3)
      << csv;
  EXPECT_GT(positives, 0) << csv;
  EXPECT_GT(tp, 0) << csv;
  EXPECT_NE(csv.find("\nother_small,test,other,positions,"), std::string::npos) << csv;
  EXPECT_NE(tool_test::readAll(kDir + "/out/results/other_small/positions/summary.txt")
                .find("live odometers continue the maps'"),
            std::string::npos);
  // A mode it does not know stops it before anything runs.
  EXPECT_EQ(tool_test::run(env(list, "BOWG_REINSPECTION_MODES=sonar") + script, log), 2);
  EXPECT_NE(tool_test::readAll(log).find("unknown mode 'sonar'"), std::string::npos)
      << tool_test::readAll(log);
}

}  // namespace
}  // namespace bowg
