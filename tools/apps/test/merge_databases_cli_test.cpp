// End-to-end tests of bowg_merge_databases: two missions' files merged into
// one that loads with both, the merge of a merge equal to the merge of the
// parts, and bad inputs refused with the file named and nothing written.
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <string>

#include "bowg/detection/loop_detector.h"
#include "bowg/vocabulary/vocabulary.h"
#include "bowg/vocabulary/vocabulary_io.h"
#include "shell_command.h"
#include "synthetic_corridor.h"
#include "synthetic_vocabulary.h"

namespace bowg {
namespace {

using tool_test::readAll;
using tool_test::run;

const std::string kDir = std::string(BOWG_TEST_OUTPUT_DIR) + "/merge_databases_cli_test";
const std::string kMerge = BOWG_MERGE_DATABASES_BIN;

std::shared_ptr<const Vocabulary> vocabulary(std::uint64_t seed) {
  return std::make_shared<Vocabulary>(testing::makeSyntheticVocabulary(10, 4, seed));
}

// Mission `name` (id `id`) over corridor metres [first, last), saved.
std::string missionFile(const std::string& file, const std::string& name, std::int64_t id,
                        int first, int last, std::uint64_t vocabulary_seed = 7) {
  LoopDetector d(vocabulary(vocabulary_seed), LoopDetectorOptions());
  d.startMission(name, id);
  const testing::Corridor c = testing::makeCorridor(60, 40, 31);
  std::mt19937_64 rng(static_cast<std::uint64_t>(id));
  for (int i = first; i < last; ++i) d.process(testing::observeCorridor(c, i, 1.0 + i, rng, 2));
  const std::string path = kDir + "/" + file;
  d.save(path);
  return path;
}

class MergeDatabasesCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ASSERT_EQ(run("rm -rf " + kDir + " && mkdir -p " + kDir), 0);
    saveVocabulary(*vocabulary(7), kDir + "/voc.bowgvoc");
  }
  static std::string merge(const std::string& args) {
    return kMerge + " " + args + " --vocabulary " + kDir + "/voc.bowgvoc";
  }
};

TEST_F(MergeDatabasesCli, MergesMissionsIntoOneFileThatMergesAgain) {
  const std::string a = missionFile("a.bowgdb", "2025-05-12", 1, 0, 20);
  const std::string b = missionFile("b.bowgdb", "2026-05-10", 2, 20, 35);
  const std::string c = missionFile("c.bowgdb", "2027-05-03", 3, 35, 50);
  const std::string log = kDir + "/ab.log";
  ASSERT_EQ(run(merge(b + " " + a + " -o " + kDir + "/ab.bowgdb"), log), 0) << readAll(log);
  EXPECT_NE(readAll(log).find("35 keyframes, 2 missions"), std::string::npos) << readAll(log);
  EXPECT_NE(readAll(log).find("mission 1 '2025-05-12': 20 keyframes"), std::string::npos);
  LoopDetector d(vocabulary(7), LoopDetectorOptions());
  d.load(kDir + "/ab.bowgdb");
  EXPECT_EQ(d.database().missions().find(2)->entries, 15u);
  ASSERT_EQ(run(merge(kDir + "/ab.bowgdb " + c + " -o " + kDir + "/ab_c.bowgdb"), log), 0)
      << readAll(log);
  ASSERT_EQ(run(merge(a + " " + b + " " + c + " -o " + kDir + "/abc.bowgdb"), log), 0)
      << readAll(log);
  EXPECT_EQ(readAll(kDir + "/ab_c.bowgdb"), readAll(kDir + "/abc.bowgdb"));
  EXPECT_FALSE(readAll(kDir + "/abc.bowgdb").empty());
}

// Exit 1, the reason and the file in the message, and no output file.
void expectRefused(const std::string& command, const std::string& out, const std::string& why,
                   const std::string& file) {
  const std::string log = kDir + "/refused.log";
  EXPECT_EQ(run(command, log), 1) << readAll(log);
  EXPECT_NE(readAll(log).find(why), std::string::npos) << readAll(log);
  EXPECT_NE(readAll(log).find(file), std::string::npos) << readAll(log);
  EXPECT_TRUE(readAll(out).empty()) << out << " written";
}

TEST_F(MergeDatabasesCli, BadInputsAreRefusedNamingTheFile) {
  const std::string a = missionFile("bad_a.bowgdb", "2025", 1, 0, 20);
  const std::string twin = missionFile("bad_twin.bowgdb", "2026", 1, 20, 30);
  const std::string foreign = missionFile("bad_foreign.bowgdb", "2027", 4, 30, 40, 99);
  const std::string truncated = kDir + "/bad_truncated.bowgdb";
  const std::string bytes = readAll(a);
  tool_test::writeAll(truncated, bytes.substr(0, bytes.size() - 100));
  const std::string out = kDir + "/bad_out.bowgdb";
  expectRefused(merge(a + " " + a + " -o " + out), out, "merged with itself", a);
  expectRefused(merge(a + " " + twin + " -o " + out), out, "both hold mission 1", twin);
  expectRefused(merge(a + " " + foreign + " -o " + out), out, "another vocabulary", foreign);
  expectRefused(merge(a + " " + truncated + " -o " + out), out, "truncated", truncated);
  const std::string log = kDir + "/usage.log";
  EXPECT_EQ(run(kMerge + " " + a + " -o " + out + " --vocabulary " + kDir + "/voc.bowgvoc", log),
            2);
  EXPECT_NE(readAll(log).find("usage:"), std::string::npos);
  EXPECT_EQ(run(kMerge + " " + a + " " + a + " --vocabulary " + kDir + "/voc.bowgvoc", log), 2);
  EXPECT_EQ(run(kMerge + " " + a + " " + twin + " -o " + out + " --bogus", log), 2);
  EXPECT_TRUE(readAll(out).empty());
}

}  // namespace
}  // namespace bowg
