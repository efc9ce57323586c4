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
// (mean, median, p95, max): features (wall), detector_total and features_cpu
// (the extraction's CPU time), each given as "MEAN P95".
std::string run(const std::string& name, const std::string& features, const std::string& detection,
                const std::string& features_cpu) {
  const std::string dir = kDir + "/" + name;
  tool_test::run("mkdir -p " + dir);
  const auto line = [](const std::string& stage, const std::string& mean_p95) {
    const std::size_t space = mean_p95.find(' ');
    return "  " + stage + std::string(15 - stage.size(), ' ') + "  " + mean_p95.substr(0, space) +
           "    3.16    " + mean_p95.substr(space + 1) + "   14.84\n";
  };
  tool_test::writeAll(dir + "/summary.txt",
                      "per-keyframe timing (ms): mean / median / p95 / max\n"
                      "configured (1.4 s for the run):\n" +
                          line("features", features) +
                          "  transform          0.14    0.14    0.21    0.36\n" +
                          line("detector_total", detection) + line("features_cpu", features_cpu));
  return dir;
}

TEST(CpuBudget, MediansOfTheRoundsAndTheShareOfOneCore) {
  ASSERT_EQ(tool_test::run("rm -rf " + kDir + " && mkdir -p " + kDir), 0);
  // pipe, whole keyframes on the CPU time: 3.90 + 0.50 = 4.40, 5.00 + 1.00 =
  // 6.00, 2.20 + 0.40 = 2.60; medians: features 3.50 wall, 3.90 CPU,
  // detection 0.50, keyframe 4.40, p95 of 5.50 + 1, 7.50 + 2, 4 + 0.6 -> 6.50.
  // A core's share: 4.40 ms x 5 / s = 2.2 %, x 10 = 4.4 %, x 25 = 11.0 %.
  // generic, one round: 1.45 + 0.35 = 1.80 ms (p95 2.20 + 0.50) -> 0.9 /
  // 1.8 / 4.5 %; its wall time (1.25) is not what the shares use.
  const std::string rounds = " pipe:" + run("p1", "3.50 5.00", "0.50 1.00", "3.90 5.50") +
                             " generic:" + run("g1", "1.25 2.00", "0.35 0.50", "1.45 2.20") +
                             " pipe:" + run("p2", "4.00 7.00", "1.00 2.00", "5.00 7.50") +
                             " pipe:" + run("p3", "2.00 4.00", "0.40 0.60", "2.20 4.00");
  const std::string log = kDir + "/table.log";
  ASSERT_EQ(tool_test::run(kScript + " --csv " + kDir + "/budget.csv" + rounds, log), 0)
      << tool_test::readAll(log);
  const std::string table = tool_test::readAll(log);
  EXPECT_NE(table.find("| pipe | 3.50 (3.90) | 0.50 | 4.40 (6.50) | 2.2 % / 4.4 % / 11.0 % |"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("| generic | 1.25 (1.45) | 0.35 | 1.80 (2.70) | 0.9 % / 1.8 % / 4.5 % |"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("(median over pipe 3, generic 1 rounds per preset)"), std::string::npos)
      << table;
  const std::string csv = tool_test::readAll(kDir + "/budget.csv");
  EXPECT_EQ(csv.find("preset,rounds,features_ms,features_cpu_ms,detection_ms,keyframe_ms,"
                     "keyframe_p95_ms,core_share_at_5_hz,core_share_at_10_hz,core_share_at_25_hz"),
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
  // A summary without the extraction's CPU time says which stage is missing.
  const std::string wall_only = kDir + "/wall_only";
  ASSERT_EQ(tool_test::run("mkdir -p " + wall_only), 0);
  tool_test::writeAll(wall_only + "/summary.txt",
                      "per-keyframe timing (ms): mean / median / p95 / max\n"
                      "  features           3.10    3.16    4.00   14.84\n"
                      "  detector_total     0.50    0.45    1.00    2.00\n");
  EXPECT_NE(tool_test::run(kScript + " pipe:" + wall_only, log), 0);
  EXPECT_NE(tool_test::readAll(log).find(wall_only + "/summary.txt: no features_cpu timing"),
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
