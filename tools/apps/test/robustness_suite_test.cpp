// scripts/robustness_suite.sh end to end on a short list of its own: two
// rendered sequences (a closed circuit driven twice at 20 cm spacing, a route
// without revisits), the table, the CSV and the per-half summary lines.
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
                          " BOWG_SUITE_DIR=" + kDir + "/out BOWG_TOOLS_DIR=" +
                          BOWG_TOOLS_BIN_DIR + " BOWG_SUITE_THRESHOLDS=1,1.2,1.5 ";
  const std::string script = std::string(BOWG_REPO_DIR) + "/scripts/robustness_suite.sh";
  const std::string log = kDir + "/suite.log";
  ASSERT_EQ(tool_test::run(env + script, log), 0) << tool_test::readAll(log);
  const std::string printed = tool_test::readAll(log);
  // The table names both sequences and their halves; the summary has a line
  // per half and row.
  EXPECT_NE(printed.find("circuit_twice"), std::string::npos) << printed;
  EXPECT_NE(printed.find("straight_once"), std::string::npos) << printed;
  EXPECT_NE(printed.find("tuning configured     R@100%P min"), std::string::npos) << printed;
  EXPECT_NE(printed.find("test   paper_bow      0 loops on 1 sequences without revisits"),
            std::string::npos)
      << printed;
  const std::string csv = tool_test::readAll(kDir + "/out/suite.csv");
  EXPECT_EQ(csv.find("sequence,half,revisits,paper_bow_recall_at_100p,paper_bow_loops,"
                     "paper_recall_at_100p,paper_loops,configured_recall_at_100p,"
                     "configured_loops\n"),
            0u)
      << csv;
  EXPECT_NE(csv.find("\ncircuit_twice,tuning,"), std::string::npos) << csv;
  // No revisit: the recall cells are empty and no row reports a loop.
  EXPECT_NE(csv.find("\nstraight_once,test,0,,0,,0,,0\n"), std::string::npos) << csv;

  // The quick subset keeps only the sequences marked "yes"; a second run
  // reuses the rendered frames (the generator is not run again).
  ASSERT_EQ(tool_test::run(env + "BOWG_SUITE_QUICK=1 " + script, log), 0)
      << tool_test::readAll(log);
  const std::string quick = tool_test::readAll(log);
  EXPECT_EQ(quick.find("circuit_twice"), std::string::npos) << quick;
  EXPECT_EQ(quick.find("render ("), std::string::npos) << "re-rendered a cached sequence:\n"
                                                        << quick;
  // A list that cannot be read is an error that names it.
  EXPECT_EQ(tool_test::run("BOWG_SKIP_DEPS=1 BOWG_SKIP_BUILD=1 BOWG_SUITE_LIST=" + kDir +
                               "/missing.txt " + script,
                           log),
            2);
  EXPECT_NE(tool_test::readAll(log).find("missing.txt"), std::string::npos);
}

}  // namespace
}  // namespace bowg
