// Starting the loop detector as an operator does, on the test's own master
// (roscore on a free port), each start for a few seconds with its log
// captured (a driver, not a rostest):
//  - bowg.launch twice, as an operator fixing a typo does: first with a
//    config that has a misspelled key (the nodelet refuses to start, naming
//    it), then with the key fixed. The second start must succeed: the launch
//    file clears the nodelet's private parameters, so the misspelled key the
//    first launch left on the parameter server is not read again;
//  - the standalone loop_detector_node with a missing vocabulary exits 1,
//    naming the file, instead of running on without a detector.
#include <gtest/gtest.h>
#include <unistd.h>

#include <string>

#include "shell_command.h"

namespace bowg {
namespace {

using tool_test::freePort;
using tool_test::readAll;
using tool_test::run;
using tool_test::writeAll;

const std::string kDir = std::string(BOWG_TEST_OUTPUT_DIR) + "/startup_test";

// A master of the test's own for the whole test.
class Startup : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = kDir + "/" + ::testing::UnitTest::GetInstance()->current_test_info()->name();
    ASSERT_EQ(run("rm -rf " + dir_ + " && mkdir -p " + dir_), 0);
    const int port = freePort();
    ASSERT_GT(port, 0);
    env_ = "env ROS_MASTER_URI=http://127.0.0.1:" + std::to_string(port) + " ROS_HOME=" + dir_ +
           "/ros_home ";
    ASSERT_EQ(run(env_ + "bash -c 'roscore -p " + std::to_string(port) + " > " + dir_ +
                  "/roscore.log 2>&1 & echo $! > " + dir_ + "/roscore.pid'"),
              0);
    ::sleep(3);
  }
  void TearDown() override { run("kill -INT $(cat " + dir_ + "/roscore.pid)"); }

  std::string dir_, env_;
};

TEST_F(Startup, AFixedTypoIsFixedOnTheSameMaster) {
  const std::string preset = readAll(std::string(BOWG_REPO_DIR) + "/config/pipe.yaml");
  ASSERT_NE(preset.find("\nlambda_1:"), std::string::npos);
  std::string typo = preset;
  typo.replace(typo.find("\nlambda_1:"), 10, "\nlambda1:");
  writeAll(dir_ + "/typo.yaml", typo);
  writeAll(dir_ + "/fixed.yaml", preset);
  const auto launch = [&](const std::string& config, const std::string& log) {
    run(env_ +
            "timeout -s INT 25 roslaunch bowg_ros bowg.launch image:=/camera/image_raw "
            "config:=" +
            dir_ + "/" + config,
        dir_ + "/" + log);
    return readAll(dir_ + "/" + log);
  };
  const std::string first = launch("typo.yaml", "typo.log");
  const std::string second = launch("fixed.yaml", "fixed.log");
  // The misspelled key is refused by name; the fixed config starts.
  EXPECT_NE(first.find("lambda1"), std::string::npos) << first;
  EXPECT_EQ(first.find("bowg_ros ready"), std::string::npos) << first;
  EXPECT_NE(second.find("bowg_ros ready"), std::string::npos) << second;
  EXPECT_EQ(second.find("lambda1"), std::string::npos) << second;
}

TEST_F(Startup, TheStandaloneNodeExitsNonZeroWhenTheNodeletDoesNotStart) {
  const std::string log = dir_ + "/node.log";
  const int status = run(env_ + "timeout -s INT 30 " + std::string(BOWG_TOOLS_BIN_DIR) +
                             "/loop_detector_node _vocabulary_path:=/nonexistent/voc.bowgvoc",
                         log);
  EXPECT_EQ(status, 1) << readAll(log);  // 124 would be the timeout: still running
  EXPECT_NE(readAll(log).find("not started"), std::string::npos) << readAll(log);
  EXPECT_NE(readAll(log).find("/nonexistent/voc.bowgvoc"), std::string::npos) << readAll(log);
}

}  // namespace
}  // namespace bowg
