// A bounded multi-producer queue between the camera callback and the worker
// thread: push() never blocks, so the camera callback
// never waits for the detector; when the queue is full the OLDEST item is
// dropped (the newest image is the most useful to a loop detector that runs
// behind) and counted for the diagnostics. ROS-free.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <stdexcept>

namespace bowg_ros {

template <typename T>
class BoundedQueue {
 public:
  /// capacity >= 1, else std::invalid_argument.
  explicit BoundedQueue(std::size_t capacity) : capacity_(capacity) {
    if (capacity == 0) throw std::invalid_argument("BoundedQueue: capacity must be >= 1");
  }

  /// Adds `item`; returns true when the oldest item had to be dropped.
  /// After shutdown() items are discarded (returns false).
  bool push(T item) {
    bool dropped = false;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (shutdown_) return false;
      if (items_.size() >= capacity_) {
        items_.pop_front();
        ++dropped_;
        dropped = true;
      }
      items_.push_back(std::move(item));
    }
    ready_.notify_one();
    return dropped;
  }

  /// Blocks until an item is available (returns true) or shutdown() was
  /// called (returns false; remaining items are abandoned).
  bool pop(T* item) {
    std::unique_lock<std::mutex> lock(mutex_);
    ready_.wait(lock, [this] { return shutdown_ || !items_.empty(); });
    if (shutdown_) return false;
    *item = std::move(items_.front());
    items_.pop_front();
    return true;
  }

  /// Wakes every pop() for good.
  void shutdown() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      shutdown_ = true;
    }
    ready_.notify_all();
  }

  void clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    items_.clear();
  }

  std::size_t size() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return items_.size();
  }
  std::size_t dropped() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return dropped_;
  }
  std::size_t capacity() const { return capacity_; }

 private:
  const std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<T> items_;
  std::size_t dropped_ = 0;
  bool shutdown_ = false;
};

}  // namespace bowg_ros
