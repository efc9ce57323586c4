// BoundedQueue: drop-oldest semantics, drop count, blocking pop, shutdown.
#include "bowg_ros/bounded_queue.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace bowg_ros {
namespace {

TEST(BoundedQueue, DropsTheOldestWhenFullAndCountsDrops) {
  BoundedQueue<int> q(2);
  EXPECT_FALSE(q.push(1));
  EXPECT_FALSE(q.push(2));
  EXPECT_TRUE(q.push(3));  // 1 dropped
  EXPECT_TRUE(q.push(4));  // 2 dropped
  EXPECT_EQ(q.dropped(), 2u);
  EXPECT_EQ(q.size(), 2u);
  int v = 0;
  ASSERT_TRUE(q.pop(&v));
  EXPECT_EQ(v, 3);
  ASSERT_TRUE(q.pop(&v));
  EXPECT_EQ(v, 4);
  EXPECT_EQ(q.size(), 0u);
}

TEST(BoundedQueue, RejectsZeroCapacity) {
  EXPECT_THROW(BoundedQueue<int>(0), std::invalid_argument);
}

TEST(BoundedQueue, PopWaitsForAPushFromAnotherThread) {
  BoundedQueue<int> q(4);
  std::thread producer([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    q.push(42);
  });
  int v = 0;
  EXPECT_TRUE(q.pop(&v));
  EXPECT_EQ(v, 42);
  producer.join();
}

TEST(BoundedQueue, ShutdownWakesAWaitingPopAndDiscardsPushes) {
  BoundedQueue<int> q(4);
  bool result = true;
  std::thread consumer([&] {
    int v;
    result = q.pop(&v);
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  q.shutdown();
  consumer.join();
  EXPECT_FALSE(result);
  EXPECT_FALSE(q.push(1));
  EXPECT_EQ(q.size(), 0u);
}

TEST(BoundedQueue, ClearEmptiesWithoutCountingDrops) {
  BoundedQueue<int> q(3);
  q.push(1);
  q.push(2);
  q.clear();
  EXPECT_EQ(q.size(), 0u);
  EXPECT_EQ(q.dropped(), 0u);
}

}  // namespace
}  // namespace bowg_ros
