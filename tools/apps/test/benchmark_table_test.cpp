// tools/bench/benchmark_table.py (scripts/run_benchmarks.sh's closing table)
// on crafted benchmark outputs: each figure against its target, ratios and
// medians worked out by hand, the DLoopDetector rows, and clear errors.
#include <gtest/gtest.h>

#include <string>

#include "shell_command.h"

namespace bowg {
namespace {

const std::string kDir = std::string(BOWG_TEST_OUTPUT_DIR) + "/benchmark_table_test";
const std::string kScript =
    "/usr/bin/python3 " + std::string(BOWG_REPO_DIR) + "/tools/bench/benchmark_table.py";

// Google Benchmark's JSON, the fields read. ORB's time is in microseconds:
// 8,000 us = 8 ms.
const char* kFeatures =
    "{\"context\": {}, \"benchmarks\": ["
    "{\"name\": \"BM_GfttOrientedOrb\", \"run_name\": \"BM_GfttOrientedOrb\", \"cpu_time\": 4.0,"
    " \"real_time\": 4.1, \"time_unit\": \"ms\", \"features\": 480},"
    "{\"name\": \"BM_OrbMultiScaleOriented\", \"run_name\": \"BM_OrbMultiScaleOriented\","
    " \"cpu_time\": 8000.0, \"real_time\": 8100.0, \"time_unit\": \"us\", \"features\": 500}]}";

// A pipeline benchmark record: name, total_mean, total_max (ms).
std::string pipelineRecord(const std::string& name, double mean, double max) {
  return "{\"name\": \"" + name + "/iterations:500\", \"run_name\": \"" + name +
         "/iterations:500\", \"cpu_time\": 1, \"time_unit\": \"ms\", \"total_mean\": " +
         std::to_string(mean) + ", \"total_max\": " + std::to_string(max) + "},";
}

std::string pipeline(double rss) {
  return "{\"benchmarks\": [" + pipelineRecord("BM_PipelineTrained/1000/3", 0.8, 3.0) +
         pipelineRecord("BM_PipelineTrained/20000/3", 1.6, 16.0) +
         pipelineRecord("BM_Pipeline/1000", 0.5, 2.0) +
         pipelineRecord("BM_Pipeline/20000", 2.0, 9.0) +
         "{\"name\": \"BM_Memory500Features/iterations:1\", \"run_name\": "
         "\"BM_Memory500Features/iterations:1\", \"cpu_time\": 9, \"time_unit\": \"s\","
         " \"features\": 503.6, \"rss_growth_per_keyframe\": " +
         std::to_string(rss) + ", \"estimate_growth_per_keyframe\": 25000}]}";
}

std::string run(const std::string& args, const std::string& log) {
  const int rc = tool_test::run(kScript + " " + args, log);
  return std::to_string(rc) + "\n" + tool_test::readAll(log);
}

TEST(BenchmarkTable, EveryFigureAgainstItsTarget) {
  ASSERT_EQ(tool_test::run("rm -rf " + kDir + " && mkdir -p " + kDir), 0);
  tool_test::writeAll(kDir + "/features.json", kFeatures);
  tool_test::writeAll(kDir + "/pipeline.json", pipeline(24000));
  tool_test::writeAll(kDir + "/loads.txt", "52.0\n48.0\n49.0\n");
  // The loops row has no ratio and no target: not a row of the table.
  tool_test::writeAll(kDir + "/peer.csv",
                      "sequence,measure,rounds,peer,ours,ratio,ratio_min,ratio_max,target,met\n"
                      "fig8,detection mean ms,5,2.93,1.54,0.5256,0.51,0.57,<= 1/3,no\n"
                      "fig8,loops TP/FP at the operating point,1,35/9,402/2,,,,,\n");
  const std::string out =
      run("--features " + kDir + "/features.json --pipeline " + kDir + "/pipeline.json --loads " +
              kDir + "/loads.txt --peer " + kDir + "/peer.csv --csv " + kDir + "/targets.csv",
          kDir + "/table.log");
  ASSERT_EQ(out.substr(0, 2), "0\n") << out;
  // 4.0 / 8.0 ms = 0.50.
  EXPECT_NE(out.find("| <= 1 (goal 0.5) | 4.00 / 8.00 ms (480 / 500 features) | 0.50 | yes |"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("3 keyframes a place indexed), mean | < 5 ms | 1.60 ms |  | yes |"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("| same, max | < 15 ms | 16.00 ms |  | no |"), std::string::npos) << out;
  // 1.6 / 0.8 = 2.00 > 1.5, on the trained case.
  EXPECT_NE(out.find("(trained vocabulary, 3 keyframes a place indexed) | <= 1.5 | 1.60 / 0.80 "
                     "ms | 2.00 | no |"),
            std::string::npos)
      << out;
  // The stress case without a target: 2.0 / 0.5 = 4.00.
  EXPECT_NE(out.find("no revisit at 1,000) | - | 2.00 / 0.50 ms | 4.00 | - |"), std::string::npos)
      << out;
  // 24,000 / 25,000 = 0.96; the estimate 25,000 / 24,000 - 1 = +4.2 %.
  EXPECT_NE(out.find("| <= 25,000 bytes | 24000 bytes (503.6 features) | 0.96 | yes |"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("| within 5 % | 25000 / 24000 bytes (+4.2 %) |  | yes |"), std::string::npos)
      << out;
  // Median of 52, 48, 49 = 49.
  EXPECT_NE(out.find("median of 3 | <= 50 ms | 49.0 ms (min 48.0, max 52.0) |  | yes |"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("| fig8, detection mean ms: ours / DLoopDetector (median of 5 rounds) | "
                     "<= 1/3 | 1.54 / 2.93 ms | 0.53 | no |"),
            std::string::npos)
      << out;
  EXPECT_EQ(out.find("loops TP/FP"), std::string::npos) << out;
  const std::string table = tool_test::readAll(kDir + "/targets.csv");
  EXPECT_EQ(table.find("figure,target,measured,ratio,met"), 0u) << table;

  // Memory over the target and an estimate 25,000 / 26,000 - 1 = -3.8 %.
  tool_test::writeAll(kDir + "/pipeline.json", pipeline(26000));
  const std::string over = run("--features " + kDir + "/features.json --pipeline " + kDir +
                                   "/pipeline.json --loads " + kDir + "/loads.txt",
                               kDir + "/over.log");
  ASSERT_EQ(over.substr(0, 2), "0\n") << over;
  EXPECT_NE(over.find("| <= 25,000 bytes | 26000 bytes (503.6 features) | 1.04 | no |"),
            std::string::npos)
      << over;
  EXPECT_NE(over.find("(-3.8 %) |  | yes |"), std::string::npos) << over;
  EXPECT_EQ(over.find("DLoopDetector"), std::string::npos) << over;
}

TEST(BenchmarkTable, MissingFiguresAreNamed) {
  ASSERT_EQ(tool_test::run("mkdir -p " + kDir), 0);
  tool_test::writeAll(kDir + "/partial.json",
                      "{\"benchmarks\": [{\"name\": \"BM_PipelineTrained/1000/3/iterations:500\", "
                      "\"total_mean\": 1}]}");
  tool_test::writeAll(kDir + "/loads.txt", "49.0\n");
  tool_test::writeAll(kDir + "/features.json", kFeatures);
  const std::string out = run("--features " + kDir + "/features.json --pipeline " + kDir +
                                  "/partial.json --loads " + kDir + "/loads.txt",
                              kDir + "/partial.log");
  EXPECT_NE(out.substr(0, 2), "0\n") << out;
  EXPECT_NE(out.find("partial.json: no benchmark BM_PipelineTrained/20000/3"), std::string::npos)
      << out;

  tool_test::writeAll(kDir + "/empty.txt", "");
  const std::string empty = run("--features " + kDir + "/features.json --pipeline " + kDir +
                                    "/partial.json --loads " + kDir + "/empty.txt",
                                kDir + "/empty.log");
  EXPECT_NE(empty.substr(0, 2), "0\n") << empty;
  const std::string missing = run("--features " + kDir + "/absent.json --pipeline " + kDir +
                                      "/partial.json --loads " + kDir + "/loads.txt",
                                  kDir + "/absent.log");
  EXPECT_NE(missing.find("cannot read " + kDir + "/absent.json"), std::string::npos) << missing;
}

}  // namespace
}  // namespace bowg
