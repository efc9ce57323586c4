// End-to-end tests of the nodelet's database files: a ~load_database of a
// file that does not end holds up neither the frames nor the other
// services, and start-up removes what an interrupted save left behind (and
// nothing else). main() is loop_detector_rostest.cpp's (one test executable).
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <future>
#include <string>
#include <thread>

#include "nodelet_harness.h"

namespace bowg_ros {
namespace {

bool exists(const std::string& path) {
  struct stat st;
  return ::lstat(path.c_str(), &st) == 0;
}

// A service call on another thread, so that a call that never returns fails
// the test instead of hanging it.
template <class Service>
std::future<bool> callAsync(const std::string& name, Service* srv) {
  return std::async(std::launch::async, [name, srv] { return ros::service::call(name, *srv); });
}

bool answeredWithin(std::future<bool>& call, double seconds) {
  return call.wait_for(std::chrono::duration<double>(seconds)) == std::future_status::ready;
}

// The reader of a FIFO, if any, gets a few bytes and the end of the file:
// a loader still reading it fails (not a database) and returns.
void endFifo(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK);
  if (fd < 0) return;  // nobody reads it (the loader refused it without opening)
  const char junk[] = "not a database";
  if (::write(fd, junk, sizeof junk) < 0) ADD_FAILURE() << "cannot write to " << path;
  ::close(fd);
}

// Ends the FIFO however the test ends, so that a failed expectation never
// leaves the loader (and the nodelet's unload) waiting for a writer.
struct FifoEnder {
  std::string path;
  ~FifoEnder() { endFifo(path); }
};

TEST(LoopDetectorNodelet, FramesAndServicesGoOnDuringALoadThatDoesNotEnd) {
  Detector d("/fifo_load", {});
  ASSERT_TRUE(d.loaded());
  const cv::Mat world = test::makeWorld(30 * kStep + kViewWidth, kViewHeight, 5);
  std::vector<int> xs;
  for (int i = 0; i < 8; ++i) xs.push_back(i * kStep);
  ASSERT_TRUE(d.run(world, xs, 100.0));

  // A FIFO nobody writes: opening it for reading waits for a writer.
  const std::string fifo = std::string(BOWG_TEST_OUTPUT_DIR) + "/bowg_load_fifo.bowgdb";
  ::unlink(fifo.c_str());
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const FifoEnder ender{fifo};
  LoadDatabase load;
  load.request.path = fifo;
  std::future<bool> loading = callAsync(d.name() + "/load_database", &load);
  ros::WallDuration(1.0).sleep();  // the loader is at the file now

  // Frames keep being processed on the running database...
  std::vector<int> more;
  for (int i = 8; i < 16; ++i) more.push_back(i * kStep);
  EXPECT_TRUE(d.run(world, more, 200.0)) << "frames were not processed during the load";
  const std::uint32_t size = d.statuses().back().database_size;
  EXPECT_GE(size, 9u) << "the frames during the load did not reach the database";
  // ...and the other services answer.
  SaveDatabase save;
  save.request.path = std::string(BOWG_TEST_OUTPUT_DIR) + "/bowg_during_load.bowgdb";
  std::future<bool> saving = callAsync(d.name() + "/save_database", &save);
  EXPECT_TRUE(answeredWithin(saving, 20.0)) << "~save_database waited for the load";

  endFifo(fifo);
  ASSERT_TRUE(answeredWithin(loading, 30.0)) << "~load_database did not return";
  ASSERT_TRUE(loading.get());
  EXPECT_FALSE(load.response.success);
  EXPECT_NE(load.response.message.find(fifo), std::string::npos) << load.response.message;
  ASSERT_TRUE(answeredWithin(saving, 30.0));
  ASSERT_TRUE(saving.get());
  EXPECT_TRUE(save.response.success) << save.response.message;
  // The running database was kept: the next keyframe joins it.
  d.clear();
  d.publish(test::viewAt(world, 20 * kStep, kViewWidth), 300.0);
  ASSERT_TRUE(d.waitForStatuses(1, 60.0));
  EXPECT_EQ(d.statuses().back().database_size, size + 1);
  ::unlink(fifo.c_str());
  ::unlink(save.request.path.c_str());
}

TEST(LoopDetectorNodelet, StartupRemovesTheTemporaryOfAnInterruptedSaveOnly) {
  const std::string dir = std::string(BOWG_TEST_OUTPUT_DIR) + "/bowg_stale_temporaries";
  ASSERT_EQ(std::system(("rm -rf '" + dir + "' && mkdir -p '" + dir + "'").c_str()), 0);
  const auto touch = [&](const std::string& name) { std::ofstream(dir + "/" + name) << "partial"; };
  // 999999999 is above any pid_max: the writer is dead.
  const std::string stale_save = ".tmp-999999999-0-robot.bowgdb";
  const std::string stale_load = ".tmp-999999999-3-archive.bowgdb";
  const std::string live = ".tmp-" + std::to_string(static_cast<long>(::getpid())) + "-0-robot.bowgdb";
  const std::string other = ".tmp-999999999-0-notes.bowgdb";
  for (const std::string& name : {stale_save, stale_load, live, other}) touch(name);
  ASSERT_EQ(::mkfifo((dir + "/.tmp-999999999-1-robot.bowgdb").c_str(), 0600), 0);

  ErrorLog info(rosgraph_msgs::Log::INFO);
  ros::WallDuration(1.0).sleep();  // connected to /rosout before the start-up logs
  Detector d("/stale", {{"database_save_path", dir + "/robot.bowgdb"},
                        {"database_load_path", dir + "/archive.bowgdb"}});
  ASSERT_TRUE(d.loaded());
  EXPECT_FALSE(exists(dir + "/" + stale_save)) << "the save path's partial copy is still there";
  EXPECT_FALSE(exists(dir + "/" + stale_load)) << "the load path's partial copy is still there";
  EXPECT_TRUE(exists(dir + "/" + live)) << "a live writer's file was removed";
  EXPECT_TRUE(exists(dir + "/" + other)) << "another file's temporary was removed";
  EXPECT_TRUE(exists(dir + "/.tmp-999999999-1-robot.bowgdb")) << "a FIFO was removed";
  EXPECT_TRUE(info.waitFor("interrupted save of " + dir + "/robot.bowgdb", 10.0));
  // Start-up says which vocabulary it loads, and how large it is, first.
  EXPECT_TRUE(info.waitFor("loading vocabulary " + vocabularyPath() + " (", 10.0));
}

}  // namespace
}  // namespace bowg_ros
