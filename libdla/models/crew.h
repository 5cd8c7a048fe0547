#pragma once
// A small crew of threads that runs one batch of jobs at a time, for the breakdown model's
// fields (breakdown.cpp, breakdown_charges.cpp). Private to libdla.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace dla::detail {

//! Runs job(0), ..., job(count - 1) on `threads` threads, the caller's one of them; threads
//! wait between batches rather than start afresh for each.
class Crew {
 public:
  explicit Crew(int threads) {
    for (int t = 1; t < threads; ++t) helpers_.emplace_back([this] { serve(); });
  }
  ~Crew() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      closing_ = true;
    }
    wake_.notify_all();
    for (std::thread& helper : helpers_) helper.join();
  }

  //! The threads a batch runs on, the caller's among them.
  std::size_t size() const { return helpers_.size() + 1; }

  void run(std::size_t count, const std::function<void(std::size_t)>& job) {
    if (helpers_.empty()) {
      for (std::size_t i = 0; i < count; ++i) job(i);
      return;
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      job_ = &job;
      count_ = count;
      next_ = 0;
      busy_ = helpers_.size();
      ++batch_;
    }
    wake_.notify_all();
    work(job, count);
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [this] { return busy_ == 0; });
  }

 private:
  void work(const std::function<void(std::size_t)>& job, std::size_t count) {
    for (std::size_t i = next_.fetch_add(1); i < count; i = next_.fetch_add(1)) job(i);
  }
  void serve() {
    std::uint64_t seen = 0;
    for (;;) {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return closing_ || batch_ != seen; });
      if (closing_) return;
      seen = batch_;
      const std::function<void(std::size_t)>* job = job_;
      const std::size_t count = count_;
      lock.unlock();
      work(*job, count);
      lock.lock();
      if (--busy_ == 0) done_.notify_one();
    }
  }

  std::vector<std::thread> helpers_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(std::size_t)>* job_ = nullptr;
  std::size_t count_ = 0, busy_ = 0;
  std::atomic<std::size_t> next_{0};
  std::uint64_t batch_ = 0;
  bool closing_ = false;
};

}  // namespace dla::detail
