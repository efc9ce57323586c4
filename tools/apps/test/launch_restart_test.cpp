// bowg.launch on one master twice, as an operator fixing a typo does: first
// with a config that has a misspelled key (the nodelet refuses to start,
// naming it), then with the key fixed. The second start must succeed: the
// launch file clears the nodelet's private parameters, so the misspelled key
// the first launch left on the parameter server is not read again.
//
// A driver, not a rostest: each roslaunch runs on the test's own master
// (roscore on a free port), for a few seconds, with its log captured.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <string>

#include "shell_command.h"

namespace bowg {
namespace {

using tool_test::readAll;
using tool_test::run;
using tool_test::writeAll;

const std::string kDir = std::string(BOWG_TEST_OUTPUT_DIR) + "/launch_restart_test";

// A TCP port nobody listens on now (the kernel's pick).
int freePort() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof(addr);
  if (fd < 0 || ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0) {
    if (fd >= 0) ::close(fd);
    return -1;
  }
  const int port = ntohs(addr.sin_port);
  ::close(fd);
  return port;
}

TEST(LaunchRestart, AFixedTypoIsFixedOnTheSameMaster) {
  ASSERT_EQ(run("rm -rf " + kDir + " && mkdir -p " + kDir), 0);
  const std::string preset = readAll(std::string(BOWG_REPO_DIR) + "/config/pipe.yaml");
  ASSERT_NE(preset.find("\nlambda_1:"), std::string::npos);
  std::string typo = preset;
  typo.replace(typo.find("\nlambda_1:"), 10, "\nlambda1:");
  writeAll(kDir + "/typo.yaml", typo);
  writeAll(kDir + "/fixed.yaml", preset);
  const int port = freePort();
  ASSERT_GT(port, 0);
  const std::string env = "env ROS_MASTER_URI=http://127.0.0.1:" + std::to_string(port) +
                          " ROS_HOME=" + kDir + "/ros_home ";
  // The master outlives both launches.
  ASSERT_EQ(run(env + "bash -c 'roscore -p " + std::to_string(port) + " > " + kDir +
                "/roscore.log 2>&1 & echo $! > " + kDir + "/roscore.pid'"),
            0);
  const auto launch = [&](const std::string& config, const std::string& log) {
    run(env + "timeout -s INT 25 roslaunch bowg_ros bowg.launch image:=/camera/image_raw config:=" +
            kDir + "/" + config,
        kDir + "/" + log);
    return readAll(kDir + "/" + log);
  };
  ::sleep(3);
  const std::string first = launch("typo.yaml", "typo.log");
  const std::string second = launch("fixed.yaml", "fixed.log");
  run("kill -INT $(cat " + kDir + "/roscore.pid)");
  // The misspelled key is refused by name; the fixed config starts.
  EXPECT_NE(first.find("lambda1"), std::string::npos) << first;
  EXPECT_EQ(first.find("bowg_ros ready"), std::string::npos) << first;
  EXPECT_NE(second.find("bowg_ros ready"), std::string::npos) << second;
  EXPECT_EQ(second.find("lambda1"), std::string::npos) << second;
}

}  // namespace
}  // namespace bowg
