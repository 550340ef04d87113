// log_tool record: a recorder that keeps up with bursts. lcm-logger 1.3.1 leaves its LCM
// subscription at the default queue of 30 messages, so a burst (a log replayed as fast
// as possible) overflows it although the kernel delivered every datagram (README.md,
// "Does recording lose messages?"). Here the subscription queue is large and each
// message is written as soon as it is handed over. With --parts (the fleet's logger,
// fleet/mission.fleet) it records into OUT.00, OUT.01, ...: a recorder killed and restarted by
// its supervisor starts the next part, and `log_tool join` puts them together.

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <stdexcept>

#include "common/config.h"
#include "common/file_io.h"
#include "common/node/bus.h"
#include "common/node/event_log.h"
#include "common/node/lcm_bus.h"
#include "common/clock.h"
#include "logger/log_tool_commands.h"

namespace minenav {

namespace {

volatile std::sig_atomic_t g_stop = 0;

void OnStopSignal(int) { g_stop = 1; }

// Without SA_RESTART, so LCM's wait returns with EINTR and the loop sees the flag.
void InstallStopHandlers() {
  struct sigaction sa {};
  sa.sa_handler = &OnStopSignal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

// OUT.NN for the first NN (00 to 99) for which neither OUT.NN nor OUT.NN.partial (a part
// whose recorder died) exists.
std::string NextPart(const std::string& out) {
  std::error_code ec;
  for (int n = 0; n < 100; ++n) {
    const std::string part = out + (n < 10 ? ".0" : ".") + std::to_string(n);
    if (!std::filesystem::exists(part, ec) && !std::filesystem::exists(part + ".partial", ec)) return part;
  }
  throw InputError(out + ": parts .00 to .99 all exist; refusing to overwrite");
}

}  // namespace

int RunRecordCommand(const std::vector<std::string>& args) {
  std::string out, channels = ".*", url;
  double duration = 0.0, flush_interval = 0.1;
  int queue_capacity = 100000;
  ConfigSchema schema("log_tool record",
                      "Records the bus into an LCM log like lcm-logger, but with a large subscription queue so\n"
                      "bursts are not dropped. Writes OUT.partial while recording and renames it to OUT at the\n"
                      "end (SIGINT/SIGTERM or --duration). Refuses to overwrite OUT.\n"
                      "With --parts: records into OUT.00, or the next free part (OUT.01, ...) if that exists, so\n"
                      "a recorder restarted after a crash keeps what was recorded ('log_tool join OUT OUT.*').");
  bool parts = false;
  schema.AddString("out", &out, "log to write (required)");
  schema.AddString("channels", &channels, "regex of the channels to record (LCM syntax, whole name)");
  schema.AddString("lcm_url", &url, "LCM URL; empty = $LCM_DEFAULT_URL, else the design default");
  schema.AddDouble("duration", &duration, "s", "stop after this long; 0 = until SIGINT/SIGTERM", 0.0);
  schema.AddDouble("flush_interval", &flush_interval, "s", "flush the log to disk this often", 0.0, 60.0);
  schema.AddBool("parts", &parts, "record into the next free part OUT.NN instead of OUT");
  schema.AddInt("queue_capacity", &queue_capacity, "messages the LCM subscription may hold", 1, 100000000);
  if (schema.Parse(args) == ParseOutcome::kExit) return 0;
  RequireOutputPath(out, "--out");
  std::error_code ec;
  if (parts) out = NextPart(out);
  if (std::filesystem::exists(out, ec)) throw InputError(out + ": exists; refusing to overwrite");
  try {
    std::regex check(channels);
  } catch (const std::regex_error&) {
    throw UsageError("--channels '" + channels + "' is not a valid regex");
  }

  InstallStopHandlers();
  LcmBus bus(ResolveLcmUrl(url), queue_capacity);
  LogWriter writer(out);
  int64_t count = 0;
  std::string failure;  // a write error stops the recording (the bus would only count it)
  bus.Subscribe(channels, [&](const RawMessage& m) {
    if (!failure.empty()) return;
    try {
      writer.Write(std::string(m.channel), m.utime, m.data, m.size);
      ++count;
    } catch (const std::exception& e) {
      failure = e.what();
    }
  });
  const WallClock clock;
  const int64_t start = clock.NowUtime();
  int64_t last_flush = start;
  std::fprintf(stderr, "log_tool record: recording '%s' from %s to %s\n", channels.c_str(), bus.url().c_str(),
               out.c_str());
  while (!g_stop && failure.empty()) {
    bus.HandleFor(50'000);
    const int64_t now = clock.NowUtime();
    if (duration > 0.0 && static_cast<double>(now - start) >= duration * 1e6) break;
    if (static_cast<double>(now - last_flush) >= flush_interval * 1e6) {
      writer.Flush();
      last_flush = now;
    }
  }
  // Drain what is already queued before closing.
  while (failure.empty() && bus.HandleFor(0) > 0) {
  }
  if (!failure.empty()) throw std::runtime_error(failure + " (" + std::to_string(count) + " messages in " + out + ".partial)");
  writer.Close();
  std::fprintf(stderr, "log_tool record: %lld messages -> %s\n", static_cast<long long>(count), out.c_str());
  std::printf("%s\n", out.c_str());
  return 0;
}

}  // namespace minenav
