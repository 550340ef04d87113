#include "fuzz/node_fuzz.h"

#include <chrono>
#include <thread>

#include "common/log.h"
#include "common/node/log_bus.h"
#include "fuzz/scratch_file.h"
#include "tests/hostile_messages.h"

namespace minenav::fuzz {

namespace {
// What NodeRuntime::Start gives every process (--max-stamp-lead 10).
constexpr int64_t kStampLeadUs = 10'000'000;
}  // namespace

std::vector<FuzzMessage> ParseNodeFuzzInput(const uint8_t* data, size_t size, size_t num_channels) {
  std::vector<FuzzMessage> out;
  size_t pos = 0;
  while (pos + 5 <= size) {
    FuzzMessage m;
    m.channel = num_channels == 0 ? 0 : data[pos] % num_channels;
    m.delay_us = ((int64_t{data[pos + 1]} << 8) | data[pos + 2]) * 1000;
    const size_t length = (size_t{data[pos + 3]} << 8) | data[pos + 4];
    pos += 5;
    if (length > size - pos) break;
    m.data = data + pos;
    m.size = length;
    pos += length;
    out.push_back(m);
  }
  return out;
}

void NodeFuzzInputWriter::AddRaw(size_t channel, int delay_ms, const std::vector<uint8_t>& payload) {
  if (channel > 0xff || delay_ms < 0 || delay_ms > 0xffff || payload.size() > 0xffff)
    Fail("seed message out of the format's range");
  bytes_.push_back(static_cast<uint8_t>(channel));
  bytes_.push_back(static_cast<uint8_t>(delay_ms >> 8));
  bytes_.push_back(static_cast<uint8_t>(delay_ms & 0xff));
  bytes_.push_back(static_cast<uint8_t>(payload.size() >> 8));
  bytes_.push_back(static_cast<uint8_t>(payload.size() & 0xff));
  bytes_.insert(bytes_.end(), payload.begin(), payload.end());
}

// The log file and the runtime of a batch run (the runtime reads the file while it runs).
struct NodeFuzzHarness::BatchParts {
  std::unique_ptr<ScratchFile> log;
  std::unique_ptr<NodeRuntime> runtime;
};

NodeFuzzHarness::~NodeFuzzHarness() = default;

std::unique_ptr<NodeFuzzHarness> NodeFuzzHarness::Live(const std::string& process) {
  std::unique_ptr<NodeFuzzHarness> h(new NodeFuzzHarness);
  h->clock_ = std::make_unique<ManualClock>(kFuzzT0);
  h->fake_ = std::make_unique<FakeRuntime>(*h->clock_, 1.0, process);
  SetLogLevel(LogLevel::kError);
  h->fake_->bus().set_max_stamp_lead_us(kStampLeadUs);
  return h;
}

std::unique_ptr<NodeFuzzHarness> NodeFuzzHarness::Batch(const std::string& process, const uint8_t* data, size_t size,
                                                        const std::vector<std::string>& channels, int64_t settle_us) {
  testing::RawLog log;
  int64_t t = kFuzzT0;
  for (const FuzzMessage& m : ParseNodeFuzzInput(data, size, channels.size())) {
    t += m.delay_us;
    log.Add(channels[m.channel], t, std::vector<uint8_t>(m.data, m.data + m.size));
  }
  log.Add("FUZZ_END", t + settle_us, {});  // on no channel of the node: the timers run until then
  std::unique_ptr<NodeFuzzHarness> h(new NodeFuzzHarness);
  h->batch_ = std::make_unique<BatchParts>();
  h->batch_->log = std::make_unique<ScratchFile>(log.bytes().data(), log.bytes().size());
  NodeOptions options;
  options.log = h->batch_->log->path();
  options.heartbeat_period = 1.0;
  options.log_level = "error";
  options.max_stamp_lead = static_cast<double>(kStampLeadUs) * 1e-6;
  h->batch_->runtime = std::make_unique<NodeRuntime>(process, options);
  h->batch_->runtime->Start();
  NodeFuzzHarness* self = h.get();
  h->batch_->runtime->log_bus()->SetPublishCallback(
      [self](const std::string& channel, int64_t, const uint8_t* bytes, int n) {
        self->Check(channel, bytes, static_cast<size_t>(n));
      });
  return h;
}

NodeRuntime& NodeFuzzHarness::runtime() { return batch_ ? *batch_->runtime : fake_->runtime(); }
FakeBus& NodeFuzzHarness::bus() {
  if (!fake_) Fail("NodeFuzzHarness::bus() of a batch harness");
  return fake_->bus();
}
ManualClock& NodeFuzzHarness::clock() {
  if (!clock_) Fail("NodeFuzzHarness::clock() of a batch harness");
  return *clock_;
}

void NodeFuzzHarness::ExpectOutput(const std::string& channel, std::function<void(const uint8_t*, size_t)> check) {
  checks_.emplace_back(channel, std::move(check));
}

void NodeFuzzHarness::Check(const std::string& channel, const uint8_t* data, size_t size) const {
  for (const auto& [name, check] : checks_)
    if (name == channel) check(data, size);
}

void NodeFuzzHarness::CheckPublished() {
  for (const FakeBus::Message& m : bus().published()) Check(m.channel, m.data.data(), m.data.size());
  bus().ClearPublished();
}

void NodeFuzzHarness::Spin() {
  fake_->runtime().SpinOnce(0);
  CheckPublished();
}

void NodeFuzzHarness::SpinUntil(const std::function<bool()>& done, double max_seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(max_seconds);
  while (!done() && std::chrono::steady_clock::now() < end) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    clock().Advance(1000);
    Spin();
  }
}

void NodeFuzzHarness::Feed(const uint8_t* data, size_t size, const std::vector<std::string>& channels,
                           int64_t settle_us, int64_t step_us, const std::function<void()>& after_each) {
  Spin();  // the timers' first firing
  for (const FuzzMessage& m : ParseNodeFuzzInput(data, size, channels.size())) {
    clock().Advance(m.delay_us);
    bus().Inject(channels[m.channel], std::vector<uint8_t>(m.data, m.data + m.size), clock().NowUtime());
    Spin();
    if (after_each) after_each();
  }
  for (int64_t t = 0; t < settle_us; t += step_us) {
    clock().Advance(step_us);
    Spin();
  }
}

}  // namespace minenav::fuzz
