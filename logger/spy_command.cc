// log_tool spy: a terminal spy of the bus (logger/README.md, "log_tool spy"): channels, types,
// rates, sizes, bad messages and the decoded fields of each channel's latest message, redrawn
// in place, over ssh, without Java (Debian's lcm-spy dies on Java 17). --log FILE shows a
// recorded log instead; --json prints JSON once.

#include <sys/ioctl.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>

#include "common/clock.h"
#include "common/config.h"
#include "common/file_io.h"
#include "common/node/event_log.h"
#include "common/node/lcm_bus.h"
#include "logger/channel_spy.h"
#include "logger/log_tool_commands.h"

namespace minenav {

namespace {

volatile std::sig_atomic_t g_spy_stop = 0;
void OnSpyStop(int) { g_spy_stop = 1; }

int TerminalWidth() {
  winsize w{};
  if (isatty(STDOUT_FILENO) && ioctl(STDOUT_FILENO, TIOCGWINSZ, &w) == 0 && w.ws_col > 20) return w.ws_col;
  if (const char* c = std::getenv("COLUMNS"); c && std::atoi(c) > 20) return std::atoi(c);
  return 120;
}

}  // namespace

int RunSpyCommand(const std::vector<std::string>& in_args) {
  std::string channels = ".*", url, log;
  double period = 1.0, duration = 0.0, window = 2.0;
  bool json = false;
  int field_lines = 2;
  ConfigSchema schema("log_tool spy",
                      "A terminal spy of the bus: for every channel its type, rate, count, bytes, size of the\n"
                      "latest message and bad (undecodable) messages, and the decoded fields of the latest\n"
                      "message, redrawn every --period. Ctrl-C ends it. --log FILE shows a recorded log.");
  schema.AddString("channels", &channels, "regex of the channels to show (LCM syntax, whole name)");
  schema.AddString("lcm_url", &url, "LCM URL; empty = $LCM_DEFAULT_URL, else the design default");
  schema.AddString("log", &log, "show this LCM log (rates over the log's time) instead of the live bus");
  schema.AddDouble("period", &period, "s", "screen refresh period", 0.05, 60.0);
  schema.AddDouble("window", &window, "s", "rates count the messages of the last this many seconds", 0.1, 600.0);
  schema.AddDouble("duration", &duration, "s", "stop after this long; 0 = until Ctrl-C", 0.0);
  schema.AddInt("field_lines", &field_lines, "lines of decoded fields per channel", 0, 50);
  schema.AddBool("json", &json, "print JSON once (at the end of --log, or after --duration) instead of the screen");
  const std::vector<std::string> args = ExpandBareBoolFlags(in_args, {"--json"});
  if (schema.Parse(args) == ParseOutcome::kExit) return 0;
  ValidateChannelPattern(channels);

  ChannelSpy spy(window);
  if (!log.empty()) {
    const ChannelMatcher matcher(channels);
    LogReader reader(log);
    int64_t last = 0;
    while (const LogEvent* e = reader.NextInPlace()) {
      if (!matcher.Matches(e->channel)) continue;
      spy.Add(e->channel, e->data.data(), e->data.size(), e->timestamp);
      last = e->timestamp;
    }
    if (json) {
      std::printf("%s\n", spy.Json(last).dump(1, ' ', false, nlohmann::json::error_handler_t::replace).c_str());
    } else {
      std::printf("%s: %lld messages\n%s", log.c_str(), static_cast<long long>(spy.messages()),
                  spy.Text(last, TerminalWidth(), field_lines).c_str());
    }
    return 0;
  }

  struct sigaction sa {};
  sa.sa_handler = &OnSpyStop;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  LcmBus bus(ResolveLcmUrl(url), 100000);
  bus.Subscribe(channels, [&](const RawMessage& m) {
    spy.Add(m.channel, m.data, static_cast<size_t>(m.size), m.utime);
  });
  const WallClock clock;
  const int64_t start = clock.NowUtime();
  int64_t next_draw = start;
  const bool screen = !json;
  while (!g_spy_stop) {
    bus.HandleFor(20'000);
    const int64_t now = clock.NowUtime();
    if (duration > 0.0 && static_cast<double>(now - start) >= duration * 1e6) break;
    if (screen && now >= next_draw) {
      next_draw = now + static_cast<int64_t>(period * 1e6);
      // Home and clear, then the table: one write, so the screen does not flicker.
      std::string frame = "\x1b[H\x1b[2J";
      frame += "log_tool spy  " + bus.url() + "  " + std::to_string(spy.messages()) + " messages  (Ctrl-C ends)\n";
      frame += spy.Text(now, TerminalWidth(), field_lines);
      std::fwrite(frame.data(), 1, frame.size(), stdout);
      std::fflush(stdout);
    }
  }
  if (json) std::printf("%s\n", spy.Json(clock.NowUtime()).dump(1, ' ', false, nlohmann::json::error_handler_t::replace).c_str());
  return 0;
}

}  // namespace minenav
