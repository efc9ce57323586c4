// scripts/install_deps.sh against a fake apt: every package missing (a fake
// dpkg-query), root (a fake id), and an apt-get whose lock another process
// holds for its first calls. The script waits for the lock, stops on any
// other failure at once, and gives up after BOWG_APT_LOCK_WAIT seconds. The
// fake sleep returns at once, counting the seconds asked for.
#include <gtest/gtest.h>

#include <string>

#include "shell_command.h"

namespace bowg {
namespace {

using tool_test::readAll;
using tool_test::run;
using tool_test::writeAll;

const std::string kDir = std::string(BOWG_TEST_OUTPUT_DIR) + "/install_deps_test";

// A fake PATH in `dir`: apt-get fails with apt's lock message while the
// counter file holds a positive number (decremented per call), then fails
// with `then_message` (empty: succeeds); every call's arguments are logged.
void fakeApt(const std::string& dir, int locked_calls, const std::string& then_message = "") {
  ASSERT_EQ(run("rm -rf " + dir + " && mkdir -p " + dir + "/bin"), 0);
  writeAll(dir + "/locked", std::to_string(locked_calls) + "\n");
  writeAll(dir + "/bin/dpkg-query", "#!/bin/sh\nexit 1\n");
  writeAll(dir + "/bin/id", "#!/bin/sh\necho 0\n");
  writeAll(dir + "/bin/sleep", "#!/bin/sh\necho \"$1\" >> " + dir + "/slept\n");
  writeAll(dir + "/bin/apt-get",
           "#!/bin/sh\necho \"$*\" >> " + dir + "/calls\nn=$(cat " + dir +
               "/locked)\nif [ \"$n\" -gt 0 ]; then echo $((n - 1)) > " + dir +
               "/locked\n  echo 'E: Could not get lock /var/lib/dpkg/lock-frontend. It is held by "
               "process 4242 (unattended-upgr)' >&2\n  exit 100\nfi\n" +
               (then_message.empty() ? std::string("exit 0\n")
                                     : "echo '" + then_message + "' >&2\nexit 100\n"));
  ASSERT_EQ(run("chmod +x " + dir + "/bin/*"), 0);
}

std::string script() { return std::string(BOWG_REPO_DIR) + "/scripts/install_deps.sh"; }

int lines(const std::string& text) {
  int n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

TEST(InstallDeps, WaitsWhileAnotherProcessHoldsAptsLock) {
  const std::string dir = kDir + "/held_twice";
  fakeApt(dir, 2);
  const std::string log = dir + "/log";
  ASSERT_EQ(run("PATH=" + dir + "/bin:$PATH bash " + script(), log), 0) << readAll(log);
  EXPECT_NE(readAll(log).find("apt's lock is held by another process; waiting"), std::string::npos)
      << readAll(log);
  // Two refused calls of the update, then the update and the install.
  const std::string calls = readAll(dir + "/calls");
  EXPECT_EQ(lines(calls), 4) << calls;
  EXPECT_NE(calls.find("-o DPkg::Lock::Timeout=60 install -y"), std::string::npos) << calls;
  EXPECT_EQ(readAll(dir + "/slept"), "5\n5\n");
}

TEST(InstallDeps, AnyOtherFailureStopsAtOnceWithAptsMessage) {
  const std::string dir = kDir + "/no_such_package";
  fakeApt(dir, 0, "E: Unable to locate package libfoo-dev");
  const std::string log = dir + "/log";
  EXPECT_EQ(run("PATH=" + dir + "/bin:$PATH bash " + script(), log), 100);
  EXPECT_NE(readAll(log).find("E: Unable to locate package libfoo-dev"), std::string::npos)
      << readAll(log);
  EXPECT_EQ(lines(readAll(dir + "/calls")), 1);
  EXPECT_EQ(readAll(dir + "/slept"), "");
}

TEST(InstallDeps, GivesUpAfterTheLimitNamingIt) {
  const std::string dir = kDir + "/held_forever";
  fakeApt(dir, 1000);
  const std::string log = dir + "/log";
  EXPECT_EQ(run("BOWG_APT_LOCK_WAIT=10 PATH=" + dir + "/bin:$PATH bash " + script(), log), 100);
  EXPECT_NE(readAll(log).find("apt's lock still held after 10 s (BOWG_APT_LOCK_WAIT)"),
            std::string::npos)
      << readAll(log);
  EXPECT_NE(readAll(log).find("Could not get lock"), std::string::npos);
  EXPECT_EQ(lines(readAll(dir + "/calls")), 3);  // at 0, 5 and 10 s
}

}  // namespace
}  // namespace bowg
