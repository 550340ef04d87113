#pragma once
// A thread that does a node's slow work (mapping a scan, refining) so that message handling
// never waits for it. The node thread pushes jobs; the worker handles them one at a time, in
// order; what a job produces goes to an outbox that the node thread empties (on a timer), so
// the bus and its counters are touched by one thread only.
//
//   BackgroundWorker<SyncedScan, Answer> worker(100, [&](SyncedScan& s) { return Map(s); });
//   if (auto dropped = worker.Push(std::move(scan))) AnswerDropped(*dropped);   // node thread
//   runtime.AddTimer(0.01, [&](int64_t) { for (Answer& a : worker.TakeOutbox()) Publish(a); });
//   std::deque<SyncedScan> not_done = worker.Stop();                             // at shutdown
//
// Bounded (issue 11: unbounded, 10 000 scans at 1 kHz took a mapper's RSS from 7 to 98 MB
// and left its map five minutes behind): a job pushed onto a full queue pushes out the
// OLDEST waiting job, which Push returns so the caller can answer and count it. Whoever waits
// for an answer wants the newest; the oldest is the stalest, and the delay from a job to its
// result stays at most capacity x handling time.
//
// Stop() lets the job under way finish, joins the thread and returns the jobs still queued
// (the backlog): draining a backlog at shutdown took minutes. A handler that throws loses
// that job's result only (logged); the worker goes on with the next.

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>
#include <vector>

#include "common/log.h"

namespace minenav {

template <typename Job, typename Result>
class BackgroundWorker {
 public:
  // Runs on the worker thread, one job at a time.
  using Handler = std::function<Result(Job& job)>;

  // Starts the thread. `capacity` >= 1 jobs may wait.
  BackgroundWorker(size_t capacity, Handler handler)
      : capacity_(capacity < 1 ? 1 : capacity), handler_(std::move(handler)), thread_([this] { Loop(); }) {}
  ~BackgroundWorker() { Stop(); }
  BackgroundWorker(const BackgroundWorker&) = delete;
  BackgroundWorker& operator=(const BackgroundWorker&) = delete;

  // Queues a job; returns the job pushed out to make room (the oldest waiting), if any.
  // After Stop() the job is not queued: it is returned as if dropped.
  std::optional<Job> Push(Job job) {
    std::optional<Job> dropped;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (stopping_) return job;
      if (queue_.size() >= capacity_) {
        dropped = std::move(queue_.front());
        queue_.pop_front();
      }
      queue_.push_back(std::move(job));
    }
    wake_.notify_one();
    return dropped;
  }

  // The results made since the last call, in the order of their jobs.
  std::vector<Result> TakeOutbox() {
    std::lock_guard<std::mutex> lock(mutex_);
    return std::exchange(outbox_, {});
  }

  // No job is started after this one (the one under way finishes); returns at once.
  void RequestStop() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_one();
  }

  // Lets the job under way finish, stops the thread and returns the jobs still queued (not
  // handled), oldest first. Idempotent: a second call returns nothing.
  std::deque<Job> Stop() {
    RequestStop();
    if (thread_.joinable()) thread_.join();
    std::lock_guard<std::mutex> lock(mutex_);
    return std::exchange(queue_, {});
  }

  size_t capacity() const { return capacity_; }
  // Jobs waiting now (not the one under way).
  size_t queued() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return queue_.size();
  }

 private:
  void Loop() {
    for (;;) {
      Job job;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
        if (stopping_) return;
        job = std::move(queue_.front());
        queue_.pop_front();
      }
      std::optional<Result> result;
      try {
        result = handler_(job);  // no lock held: the node thread keeps queuing
      } catch (const std::exception& e) {
        MINENAV_LOG(kError) << "background job failed: " << e.what();
      }
      if (!result) continue;
      std::lock_guard<std::mutex> lock(mutex_);
      outbox_.push_back(std::move(*result));
    }
  }

  const size_t capacity_;
  Handler handler_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Job> queue_;
  std::vector<Result> outbox_;
  bool stopping_ = false;
  std::thread thread_;  // last: starts after the members it uses exist
};

}  // namespace minenav
