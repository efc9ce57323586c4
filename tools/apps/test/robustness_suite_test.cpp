// scripts/robustness_suite.sh end to end on a short list of its own: two
// rendered sequences (a closed circuit driven twice at 20 cm spacing, a route
// without revisits), each in the three input modes (odometry positions, an
// odometer alone, images alone), the table, the CSV and the per-half summary
// lines.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "shell_command.h"

namespace bowg {
namespace {

const std::string kDir = std::string(BOWG_TEST_OUTPUT_DIR) + "/robustness_suite_test";

TEST(RobustnessSuite, RendersEvaluatesAndTabulatesAListOfSequences) {
  ASSERT_EQ(tool_test::run("rm -rf " + kDir + " && mkdir -p " + kDir), 0);
  const std::string list = kDir + "/list.txt";
  {
    std::ofstream out(list);
    out << "# a comment, then two sequences\n"
        << "circuit_twice | tuning | no | render | --seed 5 --route circuit --laps 2 --rate 1 "
           "--marks-per-metre 8\n"
        << "\n"
        << "straight_once | test | yes | render | --seed 6 --route no-revisit --rate 1 "
           "--marks-per-metre 8\n";
  }
  const std::string env = "BOWG_SKIP_DEPS=1 BOWG_SKIP_BUILD=1 BOWG_SUITE_LIST=" + list +
                          " BOWG_SUITE_DIR=" + kDir + "/out BOWG_TOOLS_DIR=" + BOWG_TOOLS_BIN_DIR +
                          " BOWG_SUITE_THRESHOLDS=1,1.2,1.5 ";
  const std::string script = std::string(BOWG_REPO_DIR) + "/scripts/robustness_suite.sh";
  const std::string log = kDir + "/suite.log";
  ASSERT_EQ(tool_test::run(env + script, log), 0) << tool_test::readAll(log);
  const std::string printed = tool_test::readAll(log);
  // The table names both sequences and their halves; the summary has a line
  // per half, row and mode.
  EXPECT_NE(printed.find("circuit_twice"), std::string::npos) << printed;
  EXPECT_NE(printed.find("straight_once"), std::string::npos) << printed;
  EXPECT_NE(printed.find("   render " + kDir + "/out/sequences/straight_once ("), std::string::npos)
      << printed;
  for (const char* mode : {"positions", "odometer ", "images   "}) {
    EXPECT_NE(
        printed.find(std::string("tuning configured   ") + mode + " at the threshold: recall min"),
        std::string::npos)
        << mode << "\n"
        << printed;
    // The product publishes nothing where there is no revisit; the baselines'
    // false loops there are counted on a line of their own.
    EXPECT_NE(printed.find(std::string("test   configured   ") + mode +
                           " 0 loops on 1 sequences without revisits"),
              std::string::npos)
        << mode << "\n"
        << printed;
    EXPECT_NE(printed.find(std::string("test   paper_bow    ") + mode), std::string::npos)
        << mode << "\n"
        << printed;
  }
  // Each mode ran the evaluator with what that robot has: the positions as
  // well as the odometer, the odometer alone, nothing.
  const std::string out = kDir + "/out/results/circuit_twice/";
  EXPECT_NE(
      tool_test::readAll(out + "positions/summary.txt").find("odometry: positions and odometer"),
      std::string::npos);
  EXPECT_NE(tool_test::readAll(out + "odometer/summary.txt").find("odometry: odometer only"),
            std::string::npos);
  EXPECT_NE(tool_test::readAll(out + "images/summary.txt").find("odometry: none"),
            std::string::npos);
  const std::string csv = tool_test::readAll(kDir + "/out/suite.csv");
  EXPECT_EQ(csv.find("sequence,half,mode,revisits,row,precision,recall,true_loops,false_loops,"
                     "recall_at_100p,loops\n"),
            0u)
      << csv;
  for (const char* mode : {"positions", "odometer", "images"}) {
    EXPECT_NE(csv.find(std::string("\ncircuit_twice,tuning,") + mode + ","), std::string::npos)
        << csv;
    // No revisit: the precision, recall and R@100%P cells are empty and no
    // row reports a loop.
    EXPECT_NE(csv.find(std::string("\nstraight_once,test,") + mode + ",0,configured,,,0,0,,0\n"),
              std::string::npos)
        << csv;
  }
  // Recall by the revisits' offset to the earlier pass's nearest keyframe:
  // the rendered circuit's revisits only (the other sequence has none).
  EXPECT_NE(printed.find("revisit queries by offset to the nearest true match (configured "
                         "row, positions mode; circuit_twice)"),
            std::string::npos)
      << printed;
  const std::string offsets = tool_test::readAll(kDir + "/out/revisit_offsets.csv");
  EXPECT_EQ(offsets.find("offset,queries,closed,recall,median_inliers_true,verified_true\n"), 0u)
      << offsets;
  EXPECT_NE(offsets.find(" cm,"), std::string::npos) << offsets;

  // The quick subset keeps only the sequences marked "yes"; a second run
  // reuses the rendered frames (the generator is not run again).
  ASSERT_EQ(tool_test::run(env + "BOWG_SUITE_QUICK=1 " + script, log), 0)
      << tool_test::readAll(log);
  const std::string quick = tool_test::readAll(log);
  EXPECT_EQ(quick.find("circuit_twice"), std::string::npos) << quick;
  EXPECT_EQ(quick.find("   render "), std::string::npos) << "re-rendered a cached sequence:\n"
                                                         << quick;
  // Render only (the benchmarks' inputs): the selected sequence rendered
  // into a new folder and named, nothing evaluated.
  const std::string render_env =
      "BOWG_SKIP_DEPS=1 BOWG_SKIP_BUILD=1 BOWG_SUITE_LIST=" + list + " BOWG_SUITE_DIR=" + kDir +
      "/rendered BOWG_TOOLS_DIR=" + BOWG_TOOLS_BIN_DIR + " BOWG_SUITE_RENDER_ONLY=1 ";
  ASSERT_EQ(tool_test::run(render_env + "BOWG_SUITE_ONLY=^straight_once$ " + script, log), 0)
      << tool_test::readAll(log);
  const std::string rendered = tool_test::readAll(log);
  EXPECT_NE(rendered.find("rendered: " + kDir + "/rendered/sequences/straight_once\n"),
            std::string::npos)
      << rendered;
  EXPECT_EQ(rendered.find("circuit_twice"), std::string::npos) << rendered;
  EXPECT_EQ(rendered.find("bowg_evaluate"), std::string::npos) << rendered;
  EXPECT_FALSE(
      tool_test::readAll(kDir + "/rendered/sequences/straight_once/ground_truth.txt").empty());
  EXPECT_EQ(tool_test::run("test -z \"$(ls -A " + kDir + "/rendered/results)\""), 0) << "evaluated";
  // Nothing rendered (no sequence selected) is an error.
  EXPECT_EQ(tool_test::run(render_env + "BOWG_SUITE_ONLY=^none$ " + script, log), 1);
  EXPECT_NE(tool_test::readAll(log).find("no rendered sequence selected"), std::string::npos)
      << tool_test::readAll(log);
  // An unknown input mode is an error that names it.
  EXPECT_EQ(tool_test::run(env + "BOWG_SUITE_MODES=positions,wheels " + script, log), 2);
  EXPECT_NE(tool_test::readAll(log).find("'wheels'"), std::string::npos) << tool_test::readAll(log);
  // A list that cannot be read is an error that names it.
  EXPECT_EQ(tool_test::run("BOWG_SKIP_DEPS=1 BOWG_SKIP_BUILD=1 BOWG_SUITE_LIST=" + kDir +
                               "/missing.txt " + script,
                           log),
            2);
  EXPECT_NE(tool_test::readAll(log).find("missing.txt"), std::string::npos);
}

// tools/suite/revisit_offsets.py on a suite folder written by hand: two
// revisit queries whose offsets, bins, closures and inliers are worked out
// below.
TEST(RobustnessSuite, RevisitOffsetsBinTheQueriesByTheirDistanceToTheNearestTrueMatch) {
  const std::string dir = kDir + "_offsets";
  ASSERT_EQ(tool_test::run("rm -rf " + dir + " && mkdir -p " + dir + "/sequences/hand " + dir +
                           "/results/hand/positions"),
            0);
  {
    // Frames 0-2 of a first pass 10 cm apart; frame 3 revisits 3.5 cm past
    // frame 0 (and 6.5 cm before frame 1), frame 4 0.5 cm past frame 1 and
    // 3 cm sideways: sqrt(0.5^2 + 3^2) = 3.04 cm from frame 1.
    std::ofstream poses(dir + "/sequences/hand/poses.csv");
    poses << "frame,stamp,x,y,z\n0,0,0,0,0\n1,1,0.1,0,0\n2,2,0.2,0,0\n"
          << "3,3,0.035,0,0\n4,4,0.105,0.03,0\n";
    std::ofstream truth(dir + "/sequences/hand/ground_truth.txt");
    truth << "# query: matches\n3: 0 1\n4: 1\n";
    // Query 3 closed correctly on frame 0 with 50 inliers; query 4 stopped
    // at too_few_inliers on its true match 1 with 20.
    std::ofstream keyframes(dir + "/results/hand/positions/keyframes_configured.csv");
    keyframes << "frame,status,candidate,inliers,correct\n0,database_too_small,,0,\n"
              << "1,database_too_small,,0,\n2,no_score_above_threshold,,0,\n"
              << "3,loop_detected,0,50,1\n4,too_few_inliers,1,20,\n";
  }
  const std::string log = dir + "/offsets.log";
  ASSERT_EQ(tool_test::run("/usr/bin/python3 " + std::string(BOWG_REPO_DIR) +
                               "/tools/suite/revisit_offsets.py --suite " + dir + " --csv " + dir +
                               "/offsets.csv",
                           log),
            0)
      << tool_test::readAll(log);
  // Offsets 3.5 cm (the nearer of 3.5 and 6.5) and 3.04 cm: both in 3-4 cm;
  // one of the two closed; inliers 50 and 20, median 35.
  EXPECT_EQ(tool_test::readAll(dir + "/offsets.csv"),
            "offset,queries,closed,recall,median_inliers_true,verified_true\n"
            "3-4 cm,2,1,0.5000,35.0,2\n");
  // A results file that is missing is an error that names it.
  ASSERT_EQ(tool_test::run("rm " + dir + "/results/hand/positions/keyframes_configured.csv"), 0);
  EXPECT_NE(tool_test::run("/usr/bin/python3 " + std::string(BOWG_REPO_DIR) +
                               "/tools/suite/revisit_offsets.py --suite " + dir + " hand",
                           log),
            0);
  EXPECT_NE(tool_test::readAll(log).find("keyframes_configured.csv"), std::string::npos)
      << tool_test::readAll(log);
}

}  // namespace
}  // namespace bowg
