// tools/bench/cpu_budget.py (scripts/cpu_budget.sh's table) on crafted
// rounds: the medians of the per-keyframe means, the whole keyframe and the
// share of one core, worked out by hand, and clear errors; and the script
// refusing a preset that does not exist before it builds anything.
#include <gtest/gtest.h>

#include <string>

#include "shell_command.h"

namespace bowg {
namespace {

const std::string kDir = std::string(BOWG_TEST_OUTPUT_DIR) + "/cpu_budget_test";
const std::string kScript =
    "/usr/bin/python3 " + std::string(BOWG_REPO_DIR) + "/tools/bench/cpu_budget.py";

// A bowg_evaluate output folder: the summary.txt timing lines the script reads
// (mean, median, p95, max).
std::string run(const std::string& name, const std::string& features,
                const std::string& features_p95, const std::string& detection,
                const std::string& detection_p95) {
  const std::string dir = kDir + "/" + name;
  tool_test::run("mkdir -p " + dir);
  tool_test::writeAll(dir + "/summary.txt",
                      "per-keyframe timing (ms): mean / median / p95 / max\n"
                      "configured (1.4 s for the run):\n"
                      "  features           " +
                          features + "    3.16    " + features_p95 +
                          "   14.84\n"
                          "  transform          0.14    0.14    0.21    0.36\n"
                          "  detector_total     " +
                          detection + "    1.09    " + detection_p95 + "    9.00\n");
  return dir;
}

TEST(CpuBudget, MediansOfTheRoundsAndTheShareOfOneCore) {
  ASSERT_EQ(tool_test::run("rm -rf " + kDir + " && mkdir -p " + kDir), 0);
  // pipe: whole keyframes 3.5 + 0.5 = 4.0, 4.0 + 1.0 = 5.0, 2.0 + 0.4 = 2.4;
  // medians: features 3.5, detection 0.5, keyframe 4.0, p95 of 5 + 1, 7 + 2,
  // 4 + 0.6 -> 6.0. A core's share: 4.0 ms x 5 / s = 2.0 %, x 10 = 4.0 %,
  // x 25 = 10.0 %. generic, one round: 1.25 + 0.35 = 1.6 ms -> 0.8 / 1.6 / 4.0 %.
  const std::string rounds = " pipe:" + run("p1", "3.50", "5.00", "0.50", "1.00") +
                             " generic:" + run("g1", "1.25", "2.00", "0.35", "0.50") +
                             " pipe:" + run("p2", "4.00", "7.00", "1.00", "2.00") +
                             " pipe:" + run("p3", "2.00", "4.00", "0.40", "0.60");
  const std::string log = kDir + "/table.log";
  ASSERT_EQ(tool_test::run(kScript + " --csv " + kDir + "/budget.csv" + rounds, log), 0)
      << tool_test::readAll(log);
  const std::string table = tool_test::readAll(log);
  EXPECT_NE(table.find("| pipe | 3.50 | 0.50 | 4.00 (6.00) | 2.0 % / 4.0 % / 10.0 % |"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("| generic | 1.25 | 0.35 | 1.60 (2.50) | 0.8 % / 1.6 % / 4.0 % |"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("(median over pipe 3, generic 1 rounds per preset)"), std::string::npos)
      << table;
  const std::string csv = tool_test::readAll(kDir + "/budget.csv");
  EXPECT_EQ(csv.find("preset,rounds,features_ms,detection_ms,keyframe_ms,keyframe_p95_ms,"
                     "core_share_at_5_hz,core_share_at_10_hz,core_share_at_25_hz"),
            0u)
      << csv;
}

TEST(CpuBudget, BadRoundsAreClearErrors) {
  ASSERT_EQ(tool_test::run("mkdir -p " + kDir), 0);
  const std::string log = kDir + "/bad.log";
  EXPECT_NE(tool_test::run(kScript + " no_folder", log), 0);
  EXPECT_NE(tool_test::readAll(log).find("a round is PRESET:OUTPUT, got 'no_folder'"),
            std::string::npos)
      << tool_test::readAll(log);
  const std::string untimed = kDir + "/untimed";
  ASSERT_EQ(tool_test::run("mkdir -p " + untimed), 0);
  tool_test::writeAll(untimed + "/summary.txt", "row precision recall\n");
  EXPECT_NE(tool_test::run(kScript + " pipe:" + untimed, log), 0);
  EXPECT_NE(tool_test::readAll(log).find(untimed + "/summary.txt: no per-keyframe timing"),
            std::string::npos)
      << tool_test::readAll(log);
}

TEST(CpuBudgetScript, AnUnknownPresetIsAClearError) {
  ASSERT_EQ(tool_test::run("mkdir -p " + kDir), 0);
  const std::string log = kDir + "/no_preset.log";
  const int status = tool_test::run("BOWG_BUDGET_PRESETS=pipe,no_such_preset " +
                                        std::string(BOWG_REPO_DIR) + "/scripts/cpu_budget.sh",
                                    log);
  EXPECT_EQ(status, 2) << tool_test::readAll(log);
  EXPECT_NE(tool_test::readAll(log).find("cpu_budget: no preset config/no_such_preset.yaml"),
            std::string::npos)
      << tool_test::readAll(log);
}

}  // namespace
}  // namespace bowg
