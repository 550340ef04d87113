// The node runtime's background worker: order, the bounded queue that drops its oldest job,
// the stop that returns the backlog, a failing job, and the outbox.

#include "common/node/background_worker.h"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

namespace minenav {
namespace {

// Holds the worker inside a job until Open(): the test decides what is queued meanwhile.
class Gate {
 public:
  void Open() {
    std::lock_guard<std::mutex> lock(mutex_);
    open_ = true;
    changed_.notify_all();
  }
  void Wait() {
    std::unique_lock<std::mutex> lock(mutex_);
    entered_ = true;
    changed_.notify_all();
    changed_.wait(lock, [this] { return open_; });
  }
  // Until the worker waits at the gate (it has taken its job off the queue).
  void AwaitEntered() {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return entered_; });
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  bool open_ = false, entered_ = false;
};

// Until `n` results have come out (the worker runs on its own), or 10 s.
std::vector<std::string> TakeResults(BackgroundWorker<int, std::string>& worker, size_t n) {
  std::vector<std::string> out;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (out.size() < n && std::chrono::steady_clock::now() < give_up) {
    for (std::string& r : worker.TakeOutbox()) out.push_back(std::move(r));
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return out;
}

TEST(BackgroundWorkerTest, HandlesJobsInOrderAndHandsTheResultsToTheCaller) {
  const auto caller = std::this_thread::get_id();
  bool handled_on_the_caller = false;
  BackgroundWorker<int, std::string> worker(10, [&](int& job) {
    handled_on_the_caller = handled_on_the_caller || std::this_thread::get_id() == caller;
    return "job " + std::to_string(job);
  });
  for (int k = 0; k < 5; ++k) EXPECT_FALSE(worker.Push(k).has_value());
  EXPECT_EQ(TakeResults(worker, 5), (std::vector<std::string>{"job 0", "job 1", "job 2", "job 3", "job 4"}));
  EXPECT_TRUE(worker.Stop().empty());
  EXPECT_FALSE(handled_on_the_caller);
}

TEST(BackgroundWorkerTest, AFullQueuePushesOutItsOldestJob) {
  Gate gate;
  BackgroundWorker<int, std::string> worker(2, [&](int& job) {
    if (job == 0) gate.Wait();
    return std::to_string(job);
  });
  EXPECT_FALSE(worker.Push(0).has_value());
  gate.AwaitEntered();  // job 0 is under way, the queue is empty
  EXPECT_FALSE(worker.Push(1).has_value());
  EXPECT_FALSE(worker.Push(2).has_value());
  EXPECT_EQ(worker.queued(), 2u);
  EXPECT_EQ(worker.Push(3), std::optional<int>(1));  // the oldest waiting, not the newest
  EXPECT_EQ(worker.Push(4), std::optional<int>(2));
  EXPECT_EQ(worker.queued(), 2u);
  gate.Open();
  EXPECT_EQ(TakeResults(worker, 3), (std::vector<std::string>{"0", "3", "4"}));
}

TEST(BackgroundWorkerTest, StopFinishesTheJobUnderWayAndReturnsTheBacklog) {
  Gate gate;
  BackgroundWorker<int, std::string> worker(10, [&](int& job) {
    if (job == 0) gate.Wait();
    return std::to_string(job);
  });
  worker.Push(0);
  gate.AwaitEntered();
  worker.Push(1);
  worker.Push(2);
  worker.RequestStop();
  gate.Open();
  const std::deque<int> backlog = worker.Stop();
  EXPECT_EQ(backlog, (std::deque<int>{1, 2}));
  EXPECT_EQ(worker.TakeOutbox(), (std::vector<std::string>{"0"}));  // the job under way was finished
  EXPECT_EQ(worker.Push(5), std::optional<int>(5));                 // stopped: nothing is queued
  EXPECT_TRUE(worker.Stop().empty());                               // idempotent
}

TEST(BackgroundWorkerTest, AFailingJobLosesOnlyItsOwnResult) {
  BackgroundWorker<int, std::string> worker(10, [](int& job) -> std::string {
    if (job == 1) throw std::runtime_error("bad job");
    return std::to_string(job);
  });
  for (int k = 0; k < 3; ++k) worker.Push(k);
  EXPECT_EQ(TakeResults(worker, 2), (std::vector<std::string>{"0", "2"}));
}

TEST(BackgroundWorkerTest, TheDestructorStopsWithJobsStillQueued) {
  Gate gate;
  int handled = 0;
  {
    BackgroundWorker<int, int> worker(100, [&](int& job) {
      if (job == 0) gate.Wait();
      ++handled;
      return job;
    });
    for (int k = 0; k < 50; ++k) worker.Push(k);
    gate.AwaitEntered();
    worker.RequestStop();
    gate.Open();
  }
  EXPECT_EQ(handled, 1);
}

}  // namespace
}  // namespace minenav
