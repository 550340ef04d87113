// log_tool join: one log from the parts of a recording (issue 16, "a torn ... log (power cut
// mid-write) is detected and the last good one used"). The fleet's logger runs as
// `lcm-logger --increment FILE`: a logger killed and restarted by the supervisor writes the
// next part (FILE.00, FILE.01, ...) instead of refusing to overwrite the first and giving up.
// A part whose writer died mid-event ends in a torn event: LogReader stops before it and says
// where; every whole event before it is kept, and the tear is named in one line.

#include <cstdio>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/file_io.h"
#include "common/node/event_log.h"
#include "logger/log_tool_commands.h"

namespace minenav {

int RunJoinCommand(const std::vector<std::string>& args) {
  ConfigSchema schema("log_tool join",
                      "Joins the parts of a recording (lcm-logger --increment: FILE.00, FILE.01, ...) into one\n"
                      "log, in the order given. A part cut short by its writer (kill -9, a power cut: a torn\n"
                      "last event) keeps every whole event before the tear, which is named in one line.\n"
                      "Damage inside a part is an error: exit 2, no output.");
  schema.SetPositional("OUT PART...", 2, 1 << 20);
  if (schema.Parse(args) == ParseOutcome::kExit) return 0;
  const std::vector<std::string>& positional = schema.positional();
  const std::string out = positional[0];
  const std::vector<std::string> parts(positional.begin() + 1, positional.end());
  CheckOutputIsNotInput("OUT", out, parts);
  CheckOutputIsNotInput("OUT.partial", out + ".partial", parts);
  LogWriter writer(out);  // OUT.partial until Close(): a failure leaves no OUT
  long long events = 0, torn = 0;
  for (const std::string& part : parts) {
    LogReader reader(part);
    long long kept = 0;
    while (std::optional<LogEvent> e = reader.Next()) {
      writer.Write(e->channel, e->timestamp, e->data.data(), static_cast<int>(e->data.size()));
      ++kept;
    }
    events += kept;
    if (!reader.truncation().empty()) {
      ++torn;
      std::fprintf(stderr, "log_tool join: %s: torn at its end (%s): the %lld whole events before it kept\n",
                   part.c_str(), reader.truncation().c_str(), kept);
    }
  }
  writer.Close();
  std::printf("%s: %lld events from %zu parts (%lld torn at the end)\n", out.c_str(), events, parts.size(), torn);
  return 0;
}

}  // namespace minenav
