#pragma once
// What every node's fuzz target shares (fuzz/README.md, "Node targets"). The fuzzer's input is
// a sequence of messages on the node's input channels, each after a delay of the node's clock;
// payloads are LCM encodings, valid or not, and go through the node's own Subscribe<T> path
// (wire check, decode, timestamp window, FromLcm, the handler).
//
//   * Live (NodeFuzzHarness::Live): the node on a FakeRuntime (common/node/fake_runtime.h) with
//     the fleet's 10 s timestamp window, one SpinOnce per message, then the clock runs on a few
//     seconds so that its timers act on what it got. For the nodes that answer on the node
//     thread (and the path planner, whose target waits for its worker's answers).
//   * Batch (NodeFuzzHarness::Batch): the input written as an LCM event log (in memory) and the
//     node run over it as `process --log FILE` runs: events in order, timers at log time, and
//     the nodes that map or plan on a worker thread live do it synchronously (the contour
//     mapper, the task planner), so every input is mapped or planned, repeatably.
//
// Input format, repeated until the bytes run out:
//   u8  channel   index into the target's input channels (modulo their number)
//   u16 delay     ms the clock advances before the message arrives (big-endian)
//   u16 size      payload bytes (big-endian), then the payload
//
// Findings besides crashes, sanitizer reports, hangs (-timeout) and unbounded allocation
// (-malloc_limit_mb, -rss_limit_mb): a publication on an output channel that does not decode
// as its type or that the fleet's receivers would reject (message_checks.h), i.e. the node
// passed a NaN or an absurd value on.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/clock.h"
#include "common/node/conversions.h"
#include "common/node/fake_runtime.h"
#include "fuzz/message_checks.h"

namespace minenav::fuzz {

// us: the clock's start (2023-11-14), and what seed messages are stamped relative to.
inline constexpr int64_t kFuzzT0 = 1'700'000'000'000'000;

// One message of a node fuzz input.
struct FuzzMessage {
  size_t channel = 0;  // index into the target's input channels (already reduced)
  int64_t delay_us = 0;
  const uint8_t* data = nullptr;
  size_t size = 0;
};
// Splits a fuzz input into its messages (an incomplete last one is dropped).
std::vector<FuzzMessage> ParseNodeFuzzInput(const uint8_t* data, size_t size, size_t num_channels);

// Builds a node fuzz input (the seeds: fuzz/make_seeds.cc).
class NodeFuzzInputWriter {
 public:
  void AddRaw(size_t channel, int delay_ms, const std::vector<uint8_t>& payload);
  template <typename T>
  void Add(size_t channel, int delay_ms, const T& msg) {
    AddRaw(channel, delay_ms, EncodeMessage(msg));
  }
  const std::vector<uint8_t>& bytes() const { return bytes_; }

 private:
  std::vector<uint8_t> bytes_;
};

class NodeFuzzHarness {
 public:
  ~NodeFuzzHarness();

  // A FakeRuntime named `process` with a 1 s heartbeat, the fleet's 10 s timestamp window and
  // log lines of level error only (a bad message is logged, and the fuzzer sends millions).
  static std::unique_ptr<NodeFuzzHarness> Live(const std::string& process);
  // A NodeRuntime over the input written as an LCM log (`channels` as in Feed), with one more
  // event `settle_us` after the last message so that the timers run on. The node is made on
  // runtime() and run with its Run().
  static std::unique_ptr<NodeFuzzHarness> Batch(const std::string& process, const uint8_t* data, size_t size,
                                                const std::vector<std::string>& channels,
                                                int64_t settle_us = 3'000'000);

  NodeRuntime& runtime();
  FakeBus& bus();       // live only
  ManualClock& clock();  // live only

  // Every publication on `channel` must decode as T and pass CheckAccepted (message_checks.h).
  template <typename T>
  void ExpectOutput(const std::string& channel);
  // The same with a check of one's own (calls Fail for what is wrong).
  void ExpectOutput(const std::string& channel, std::function<void(const uint8_t*, size_t)> check);

  // Live: feeds the input's messages on `channels` (each after its delay, then one Spin and
  // `after_each`), then runs the clock `settle_us` on in steps of `step_us`.
  void Feed(const uint8_t* data, size_t size, const std::vector<std::string>& channels, int64_t settle_us = 3'000'000,
            int64_t step_us = 100'000, const std::function<void()>& after_each = nullptr);
  // Live: spins once and checks what was published since the last check.
  void Spin();
  // Live: spins every millisecond of wall and clock time until `done` or `max_seconds` of wall time.
  void SpinUntil(const std::function<bool()>& done, double max_seconds);

 private:
  NodeFuzzHarness() = default;
  void Check(const std::string& channel, const uint8_t* data, size_t size) const;
  void CheckPublished();

  std::vector<std::pair<std::string, std::function<void(const uint8_t*, size_t)>>> checks_;
  // Live.
  std::unique_ptr<ManualClock> clock_;
  std::unique_ptr<FakeRuntime> fake_;
  // Batch.
  struct BatchParts;
  std::unique_ptr<BatchParts> batch_;
};

// Decodes a publication as T; fails the fuzzer when it does not decode or is rejected.
template <typename T>
void CheckPublication(const std::string& channel, const uint8_t* data, size_t size) {
  T msg{};
  std::string error;
  if (!DecodeMessage(data, static_cast<int>(size), channel, &msg, &error)) Fail("published garbage: " + error);
  try {
    CheckAccepted(msg);
  } catch (const std::exception& e) {
    Fail("published on " + channel + " what its receivers reject: " + e.what());
  }
}

template <typename T>
void NodeFuzzHarness::ExpectOutput(const std::string& channel) {
  ExpectOutput(channel, [channel](const uint8_t* data, size_t size) { CheckPublication<T>(channel, data, size); });
}

}  // namespace minenav::fuzz
