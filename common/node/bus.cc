#include "common/node/bus.h"

#include <cstdlib>
#include <regex>

#include "common/log.h"

namespace minenav {

std::string ResolveLcmUrl(const std::string& flag) {
  if (!flag.empty()) return flag;
  const char* env = std::getenv("LCM_DEFAULT_URL");
  if (env != nullptr && env[0] != '\0') return env;
  return kDefaultLcmUrl;
}

void Bus::ReportBad(std::string_view channel, const std::string& error) {
  ++counters_.messages_bad;
  auto it = bad_by_channel_.find(channel);
  if (it == bad_by_channel_.end()) it = bad_by_channel_.emplace(std::string(channel), 0).first;
  const int64_t n = ++it->second;
  // The first ten per channel, then one in a thousand: enough to diagnose, never a flood.
  if (n <= 10 || n % 1000 == 0) {
    MINENAV_LOG(kWarn) << error << (n > 1 ? " (bad message " + std::to_string(n) + " on this channel)" : "");
  }
}

bool Bus::AcceptStamp(const RawMessage& raw, int64_t stamp, const char* type_name) {
  if (max_stamp_lead_us_ <= 0) return true;
  const bool negative = stamp < 0;
  // Written so that no subtraction can overflow whatever the two times are.
  const bool too_late = !negative && raw.utime >= 0 && stamp - raw.utime > max_stamp_lead_us_;
  if (!negative && !too_late) return true;
  ++counters_.stamps_rejected;
  std::string why = "channel " + std::string(raw.channel) + ": " + type_name + " stamped " + std::to_string(stamp) +
                    " us rejected: ";
  if (negative) {
    why += "negative time";
  } else {
    why += std::to_string((stamp - raw.utime) / 1000) + " ms after it was received (window " +
           std::to_string(max_stamp_lead_us_ / 1000) + " ms, --max-stamp-lead)";
  }
  last_stamp_rejection_ = why;
  ReportBad(raw.channel, why);
  return false;
}

void Bus::ReportUnauthenticated(std::string_view channel, const std::string& why) {
  ++counters_.auth_rejected;
  auto it = auth_rejected_by_channel_.find(channel);
  if (it == auth_rejected_by_channel_.end()) it = auth_rejected_by_channel_.emplace(std::string(channel), 0).first;
  ++it->second;
  last_auth_rejection_ = why;
  ReportBad(channel, why);
}

void Bus::CountPublished(bool ok, const std::string& channel) {
  if (ok) {
    ++counters_.published;
    return;
  }
  ++counters_.publish_errors;
  if (counters_.publish_errors <= 10 || counters_.publish_errors % 1000 == 0) {
    MINENAV_LOG(kWarn) << "channel " << channel << ": publish failed (error "
                       << counters_.publish_errors << ")";
  }
}

ChannelMatcher::ChannelMatcher(std::string pattern) : pattern_(std::move(pattern)) {
  // LCM channel names are usually plain identifiers; only build a regex when needed.
  literal_ = pattern_.find_first_of(".*+?[](){}|^$\\") == std::string::npos;
  if (!literal_) {
    try {
      regex_ = std::make_shared<const std::regex>(pattern_, std::regex::ECMAScript);
    } catch (const std::regex_error&) {
      throw std::invalid_argument("channel pattern '" + pattern_ + "' is not a valid regular expression");
    }
  }
}

bool ChannelMatcher::Matches(std::string_view channel) const {
  if (literal_) return channel == pattern_;
  const auto* re = static_cast<const std::regex*>(regex_.get());
  return std::regex_match(channel.begin(), channel.end(), *re);
}

}  // namespace minenav
