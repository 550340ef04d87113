#pragma once
// What log_tool spy shows (logger/README.md, "log_tool spy"): for every channel seen, the
// message type (by fingerprint, as log_tool info names it), how many messages and bytes,
// the rate over the last few seconds, messages that did not decode, and the decoded fields
// of the latest message (its JSON form, minenav/message_json.hpp, long arrays shortened).
// No I/O and no clock: the command feeds it messages with their times and prints its text.

#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace minenav {

class ChannelSpy {
 public:
  // rate_window_s: the rate is the messages of the last this many seconds.
  explicit ChannelSpy(double rate_window_s = 2.0) : window_us_(static_cast<int64_t>(rate_window_s * 1e6)) {}

  // One message received at utime (us).
  void Add(std::string_view channel, const uint8_t* data, size_t size, int64_t utime);

  // The screen: one header line, then per channel a line of figures and up to
  // `field_lines` lines of the latest message's fields, every line at most `width` characters.
  std::string Text(int64_t now, int width, int field_lines = 2) const;
  // Everything as JSON: {"channels": [{channel, type, count, bytes, bad, rate_hz, last_error, latest}]}.
  nlohmann::json Json(int64_t now) const;

  int64_t messages() const { return messages_; }

 private:
  struct Channel {
    std::string type;  // "minenav.ladar_scan_t", or "" (foreign)
    int64_t count = 0, bytes = 0, bad = 0;
    int64_t last_size = 0;
    std::deque<int64_t> recent;  // receive times within the window
    nlohmann::json latest;       // decoded fields of the latest good message
    std::string last_error;
  };
  double Rate(const Channel& c, int64_t now) const;

  int64_t window_us_;
  int64_t messages_ = 0;
  std::map<std::string, Channel, std::less<>> channels_;
};

// `j` with every array longer than `keep` elements cut to its first `keep` and a note of
// how many there were: what fits on a screen.
nlohmann::json ShortenArrays(const nlohmann::json& j, size_t keep = 4);

}  // namespace minenav
