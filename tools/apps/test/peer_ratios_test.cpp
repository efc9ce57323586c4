// tools/bench/peer_ratios.py (scripts/peer_benchmark.sh's table) on crafted
// rounds: the per-round ratios ours / DLoopDetector and their median, worked
// out by hand, the target verdicts, the loops, and clear errors; and the
// script itself refusing to run without the peer kit.
#include <gtest/gtest.h>

#include <string>

#include "shell_command.h"

namespace bowg {
namespace {

const std::string kDir = std::string(BOWG_TEST_OUTPUT_DIR) + "/peer_ratios_test";
const std::string kScript =
    "/usr/bin/python3 " + std::string(BOWG_REPO_DIR) + "/tools/bench/peer_ratios.py";

// A peer run folder: summary.json as peer.sh writes it (the fields read).
std::string peerRun(const std::string& name, double mean, double max, double features) {
  const std::string dir = kDir + "/" + name;
  tool_test::run("mkdir -p " + dir);
  tool_test::writeAll(dir + "/summary.json",
                      "{\"timing_alpha\": 0.3, \"runs\": [{\"alpha\": 0.3, \"tp\": 38, \"fp\": 5}],"
                      " \"detect\": {\"mean\": " +
                          std::to_string(mean) +
                          ", \"median\": 1, \"p95\": 2,"
                          " \"max\": " +
                          std::to_string(max) + "}, \"features\": {\"mean\": " +
                          std::to_string(features) + ", \"max\": 9}}\n");
  return dir;
}

// A bowg_evaluate output folder: the summary.txt lines the script reads.
std::string oursRun(const std::string& name, double mean, double max, double features) {
  const std::string dir = kDir + "/" + name;
  tool_test::run("mkdir -p " + dir);
  tool_test::writeAll(
      dir + "/summary.txt",
      "input: /x (939 frames)\n"
      "row            precision  recall      F1   TP   FP  R@100%P (threshold)  loops\n"
      "bowg               0.995   0.822   0.900  402    2    0.000 (     none)    404\n\n"
      "per-keyframe timing (ms): mean / median / p95 / max\n"
      "bowg (1.4 s for the run):\n"
      "  features           " +
          std::to_string(features) +
          "    3.16    3.80   14.84\n"
          "  transform          0.14    0.14    0.21    0.36\n"
          "  detector_total     " +
          std::to_string(mean) + "    1.09    3.09   " + std::to_string(max) + "\n");
  return dir;
}

TEST(PeerRatios, MediansOfPerRoundRatiosAgainstTheTargets) {
  ASSERT_EQ(tool_test::run("rm -rf " + kDir + " && mkdir -p " + kDir), 0);
  // Round 1: detection 1.5 / 3.0 = 0.50, max 6 / 20 = 0.30, features 3 / 2 = 1.50.
  // Round 2: detection 0.5 / 2.0 = 0.25, max 4 / 10 = 0.40, features 1 / 2 = 0.50.
  // Round 3: detection 1.0 / 2.5 = 0.40, max 5 / 20 = 0.25, features 2 / 2 = 1.00.
  // Medians: 0.40 (not met), 0.30 (met), 1.00 (met: <= 1).
  const std::string rounds = " seq:" + peerRun("p1", 3.0, 20, 2) + ":" + oursRun("o1", 1.5, 6, 3) +
                             " seq:" + peerRun("p2", 2.0, 10, 2) + ":" + oursRun("o2", 0.5, 4, 1) +
                             " seq:" + peerRun("p3", 2.5, 20, 2) + ":" + oursRun("o3", 1.0, 5, 2);
  const std::string log = kDir + "/table.log";
  ASSERT_EQ(tool_test::run(kScript + " --csv " + kDir + "/ratios.csv" + rounds, log), 0)
      << tool_test::readAll(log);
  const std::string table = tool_test::readAll(log);
  EXPECT_NE(table.find("| seq | detection mean ms | 2.50 | 1.00 | 0.40 [0.25-0.50] (3 rounds) "
                       "| <= 1/3 | no |"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("| seq | detection max ms | 20.00 | 5.00 | 0.30 [0.25-0.40] (3 rounds) "
                       "| <= 1/3 | yes |"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("| seq | features mean ms | 2.00 | 2.00 | 1.00 [0.50-1.50] (3 rounds) "
                       "| <= 1 | yes |"),
            std::string::npos)
      << table;
  // Whole keyframe (features + detection mean): round 1 4.5 / 5.0 = 0.90,
  // round 2 1.5 / 4.0 = 0.375, round 3 3.0 / 4.5 = 0.667; median 0.667 > 0.5.
  EXPECT_NE(table.find("| seq | whole-keyframe mean ms | 4.50 | 3.00 | 0.67 [0.38-0.90] (3 rounds) "
                       "| <= 0.5 | no |"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("| seq | loops TP/FP at the operating point | 38/5 | 402/2 |"),
            std::string::npos)
      << table;
  const std::string csv = tool_test::readAll(kDir + "/ratios.csv");
  EXPECT_EQ(csv.find("sequence,measure,rounds,peer,ours,ratio,ratio_min,ratio_max,target,met"), 0u)
      << csv;
}

TEST(PeerRatios, BadRoundsAreClearErrors) {
  ASSERT_EQ(tool_test::run("mkdir -p " + kDir), 0);
  const std::string log = kDir + "/bad.log";
  EXPECT_NE(tool_test::run(kScript + " only_two:" + kDir, log), 0);
  EXPECT_NE(tool_test::readAll(log).find("a round is NAME:PEER_RUN:OURS_OUTPUT"), std::string::npos)
      << tool_test::readAll(log);
  const std::string empty = kDir + "/empty_run";
  ASSERT_EQ(tool_test::run("mkdir -p " + empty), 0);
  EXPECT_NE(tool_test::run(kScript + " s:" + empty + ":" + empty, log), 0);
  EXPECT_NE(tool_test::readAll(log).find("cannot read " + empty + "/summary.json"),
            std::string::npos)
      << tool_test::readAll(log);
}

TEST(PeerBenchmark, AnAbsentPeerKitIsAClearError) {
  // Before anything is installed or built: exit 2 naming the missing kit.
  ASSERT_EQ(tool_test::run("mkdir -p " + kDir), 0);
  const std::string log = kDir + "/no_kit.log";
  const int status = tool_test::run("BOWG_PEER_KIT=" + kDir + "/no_such_kit " +
                                        std::string(BOWG_REPO_DIR) + "/scripts/peer_benchmark.sh",
                                    log);
  EXPECT_EQ(status, 2) << tool_test::readAll(log);
  EXPECT_NE(
      tool_test::readAll(log).find("the peer kit is absent (" + kDir + "/no_such_kit/peer.sh)"),
      std::string::npos)
      << tool_test::readAll(log);
}

}  // namespace
}  // namespace bowg
