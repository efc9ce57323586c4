// Clustering one node of the vocabulary tree (vocabulary_trainer.cpp): binary
// k-medians with k-means++ seeding over a range of descriptor indices,
// reordered in place; and the thread helpers the training shares. Internal
// to the vocabulary stage.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <thread>
#include <vector>

#include "bowg/vocabulary/vocabulary_trainer.h"

namespace bowg {
namespace node_clustering {

// Runs fn(begin, end) over [0, n) split into `threads` contiguous parts.
template <typename Fn>
void parallelRanges(std::size_t n, int threads, Fn fn) {
  if (threads <= 1 || n < 4096) {
    fn(std::size_t(0), n);
    return;
  }
  std::vector<std::thread> pool;
  const std::size_t step =
      (n + static_cast<std::size_t>(threads) - 1) / static_cast<std::size_t>(threads);
  for (int t = 1; t < threads; ++t) {
    const std::size_t b = std::min(n, step * static_cast<std::size_t>(t));
    const std::size_t e = std::min(n, b + step);
    pool.emplace_back([=] { fn(b, e); });
  }
  fn(std::size_t(0), std::min(n, step));
  for (auto& th : pool) th.join();
}

// Runs task(i) for i in [0, n) on `threads` workers pulling indices.
template <typename Fn>
void parallelTasks(std::size_t n, int threads, Fn task) {
  if (threads <= 1 || n < 2) {
    for (std::size_t i = 0; i < n; ++i) task(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i; (i = next.fetch_add(1)) < n;) task(i);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& th : pool) th.join();
}

struct Split {
  std::vector<Descriptor> centres;  // one per non-empty child
  std::vector<std::size_t> bounds;  // child c owns items [bounds[c], bounds[c+1])
};

/// Clusters items[begin, end) (at least 2 items) into at most k children and
/// reorders the range so that each child's items are contiguous. The
/// node's generator is seeded from (options.seed, node).
Split clusterNode(const Descriptor* all, std::uint32_t* items, std::size_t begin, std::size_t end,
                  const TrainingOptions& options, NodeId node, int threads);

/// True when every descriptor of items[begin, end) is the same (a leaf).
bool allIdentical(const Descriptor* all, const std::uint32_t* items, std::size_t begin,
                  std::size_t end);

}  // namespace node_clustering
}  // namespace bowg
