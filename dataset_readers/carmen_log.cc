#include "dataset_readers/carmen_log.h"

#include <bzlib.h>
#include <zlib.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "common/angle.h"
#include "common/file_io.h"

namespace minenav {
namespace {

// ---- Decompression, streamed: the file is read in chunks and split into lines as it
// comes, so memory holds one line at a time, never the whole decompressed text (a 3 MB
// gzip bomb expands to 3 GB). A truncated stream is an error, not a shorter log.

constexpr size_t kChunkBytes = 1 << 16;

// Decompressed bytes in chunks. Read() returns 0 at the clean end of the data and throws
// InputError naming the file when the data is corrupt or ends early.
class ByteSource {
 public:
  virtual ~ByteSource() = default;
  virtual size_t Read(char* buffer, size_t capacity) = 0;
};

class PlainSource : public ByteSource {
 public:
  explicit PlainSource(const std::string& path) : path_(path), in_(path, std::ios::binary) {
    if (!in_) throw InputError(path + ": cannot open");
  }
  size_t Read(char* buffer, size_t capacity) override {
    in_.read(buffer, static_cast<std::streamsize>(capacity));
    if (in_.bad()) throw InputError(path_ + ": read error");
    return static_cast<size_t>(in_.gcount());
  }

 private:
  std::string path_;
  std::ifstream in_;
};

[[noreturn]] void ThrowTruncated(const std::string& path, const char* format) {
  throw InputError(path + ": truncated: the " + format +
                   " stream ends before its end marker (the file was cut short; the lines read so far are not "
                   "the whole log)");
}

class GzipSource : public ByteSource {
 public:
  explicit GzipSource(const std::string& path) : path_(path), file_(gzopen(path.c_str(), "rb")) {
    if (file_ == nullptr) throw InputError(path + ": cannot open");
  }
  ~GzipSource() override {
    if (file_ != nullptr) gzclose(file_);
  }
  size_t Read(char* buffer, size_t capacity) override {
    if (file_ == nullptr) return 0;  // closed at the end of the data
    const int n = gzread(file_, buffer, static_cast<unsigned>(capacity));
    // zlib reports a stream that ends without its final block and CRC/length trailer as
    // Z_BUF_ERROR ("unexpected end of file"), after handing out the bytes before the cut:
    // a file cut at a flush point decodes cleanly up to there.
    int code = Z_OK;
    const char* message = gzerror(file_, &code);
    if (code == Z_BUF_ERROR) ThrowTruncated(path_, "gzip");
    if (n < 0 || code != Z_OK)
      throw InputError(path_ + ": gzip data is corrupt (" + std::string(message ? message : "?") + ")");
    if (n == 0) {
      const int closed = gzclose(file_);
      file_ = nullptr;
      if (closed == Z_BUF_ERROR) ThrowTruncated(path_, "gzip");
      if (closed != Z_OK) throw InputError(path_ + ": gzip data is corrupt (gzclose: " + std::to_string(closed) + ")");
    }
    return static_cast<size_t>(n);
  }

 private:
  std::string path_;
  gzFile file_;
};

// A .bz2 may hold several concatenated streams (pbzip2): all are read, in order.
class Bzip2Source : public ByteSource {
 public:
  explicit Bzip2Source(const std::string& path) : path_(path), file_(std::fopen(path.c_str(), "rb"), &std::fclose) {
    if (!file_) throw InputError(path + ": cannot open");
  }
  ~Bzip2Source() override { CloseStream(); }
  size_t Read(char* buffer, size_t capacity) override {
    while (!done_) {
      if (stream_ == nullptr) OpenStream();
      int err = BZ_OK;
      const int n = BZ2_bzRead(&err, stream_, buffer, static_cast<int>(capacity));
      if (err == BZ_OK) {
        if (n > 0) return static_cast<size_t>(n);
        continue;
      }
      if (err == BZ_UNEXPECTED_EOF) ThrowTruncated(path_, "bzip2");
      if (err != BZ_STREAM_END) throw InputError(path_ + ": bzip2 data is corrupt (error " + std::to_string(err) + ")");
      // The end of one stream: keep the bytes read past it, they start the next.
      void* rest = nullptr;
      int rest_size = 0;
      BZ2_bzReadGetUnused(&err, stream_, &rest, &rest_size);
      unused_.assign(static_cast<char*>(rest), static_cast<char*>(rest) + rest_size);
      CloseStream();
      if (unused_.empty()) {
        const int c = std::fgetc(file_.get());
        if (c == EOF) done_ = true;
        else std::ungetc(c, file_.get());
      }
      if (n > 0) return static_cast<size_t>(n);
    }
    return 0;
  }

 private:
  void OpenStream() {
    int err = BZ_OK;
    stream_ = BZ2_bzReadOpen(&err, file_.get(), 0, 0, unused_.empty() ? nullptr : unused_.data(),
                             static_cast<int>(unused_.size()));
    if (err != BZ_OK) {
      CloseStream();
      throw InputError(path_ + ": cannot read bzip2 data");
    }
  }
  void CloseStream() {
    if (stream_ == nullptr) return;
    int err = BZ_OK;
    BZ2_bzReadClose(&err, stream_);
    stream_ = nullptr;
  }

  std::string path_;
  std::unique_ptr<FILE, int (*)(FILE*)> file_;
  BZFILE* stream_ = nullptr;
  std::vector<char> unused_;
  bool done_ = false;
};

std::unique_ptr<ByteSource> OpenMaybeCompressed(const std::string& path) {
  std::ifstream probe(path, std::ios::binary);
  if (!probe) throw InputError(path + ": cannot open");
  char magic[3] = {0, 0, 0};
  probe.read(magic, 3);
  const std::streamsize got = probe.gcount();
  probe.close();
  if (got >= 3 && magic[0] == 'B' && magic[1] == 'Z' && magic[2] == 'h') return std::make_unique<Bzip2Source>(path);
  if (got >= 2 && static_cast<unsigned char>(magic[0]) == 0x1f && static_cast<unsigned char>(magic[1]) == 0x8b)
    return std::make_unique<GzipSource>(path);
  return std::make_unique<PlainSource>(path);
}

[[noreturn]] void ThrowLineTooLong(const std::string& source, int64_t line_number, size_t max_line_bytes) {
  throw InputError(source + ":" + std::to_string(line_number) + ": line longer than " +
                   std::to_string(max_line_bytes) +
                   " bytes (a CARMEN line is a few KB): not a CARMEN log, or a corrupt one");
}

// ---- Parsing.

// Whitespace-separated fields of one line.
void SplitFields(std::string_view line, std::vector<std::string_view>* fields) {
  fields->clear();
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    if (i >= line.size()) break;
    size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
    fields->push_back(line.substr(i, j - i));
    i = j;
  }
}

// Input text as it may appear in a one-line error (Excerpt, or Quoted in '...'): at most
// kMaxQuotedBytes of it, then "..."; bytes that are not printable ASCII as \xHH, so a
// hostile field can neither make the message megabytes long nor break it into lines or
// send terminal escapes.
constexpr size_t kMaxQuotedBytes = 80;

std::string Excerpt(std::string_view text) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  for (size_t i = 0; i < text.size() && i < kMaxQuotedBytes; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 0xf];
    }
  }
  if (text.size() > kMaxQuotedBytes) out += "...";
  return out;
}

std::string Quoted(std::string_view text) { return "'" + Excerpt(text) + "'"; }

class LineParser {
 public:
  LineParser(const std::string& source, int64_t line_number, const std::vector<std::string_view>& fields)
      : source_(source), line_(line_number), fields_(fields) {}

  [[noreturn]] void Fail(const std::string& what) const {
    throw InputError(source_ + ":" + std::to_string(line_) + ": " + Excerpt(fields_[0]) + ": " + what);
  }

  double Double(size_t i, const char* what) const {
    const std::string_view f = fields_[i];
    double v = 0.0;
    const char* begin = f.data();
    const char* end = f.data() + f.size();
    if (!f.empty() && *begin == '+') ++begin;
    const auto r = std::from_chars(begin, end, v);
    if (r.ec != std::errc() || r.ptr != end || !std::isfinite(v))
      Fail(std::string(what) + " " + Quoted(f) + " (field " + std::to_string(i + 1) + ") is not a finite number");
    return v;
  }

  int Count(size_t i, const char* what) const {
    const std::string_view f = fields_[i];
    int v = 0;
    const auto r = std::from_chars(f.data(), f.data() + f.size(), v);
    if (r.ec != std::errc() || r.ptr != f.data() + f.size() || v < 0 || v > 1000000)
      Fail(std::string(what) + " " + Quoted(f) + " (field " + std::to_string(i + 1) +
           ") is not a count");
    return v;
  }

  // The ipc timestamp is the third field from the end.
  int64_t IpcUtime() const {
    const std::string_view f = fields_[fields_.size() - 3];
    int64_t t = 0;
    if (!ParseCarmenTimestamp(std::string(f), &t))
      Fail("ipc timestamp " + Quoted(f) + " (field " + std::to_string(fields_.size() - 2) +
           ") is not a time in seconds");
    return t;
  }

  void ExpectFields(size_t expected, const std::string& layout) const {
    if (fields_.size() != expected)
      Fail("expected " + std::to_string(expected) + " fields (" + layout + "), got " +
           std::to_string(fields_.size()));
  }
  void ExpectAtLeast(size_t expected, const std::string& layout) const {
    if (fields_.size() < expected)
      Fail("expected at least " + std::to_string(expected) + " fields (" + layout + "), got " +
           std::to_string(fields_.size()));
  }

 private:
  const std::string& source_;
  int64_t line_;
  const std::vector<std::string_view>& fields_;
};

// CARMEN's carmen_laser_get_angle_increment for the old FLASER format.
double FlaserAngleStep(int n) {
  if (n == 180 || n == 181) return kPi / 180.0;
  if (n == 360 || n == 361) return kPi / 360.0;
  if (n == 400 || n == 401) return kPi / 720.0;
  return n > 1 ? kPi / static_cast<double>(n - 1) : kPi;
}

struct ParseState {
  const CarmenReadOptions* options = nullptr;
  double front_laser_max = 0.0;  // m, from PARAM robot_front_laser_max; 0 = not given
  CarmenLog log;
};

// Ranges [first, first + n) into scan->ranges; no-return readings become NaN.
void FillRanges(const LineParser& p, size_t first, int n, LadarScan* scan, CarmenLogStats* stats) {
  scan->ranges.resize(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double r = p.Double(first + static_cast<size_t>(i), "range");
    if (r <= 0.0 || r < scan->min_range || r >= scan->max_range) {
      scan->ranges[static_cast<size_t>(i)] = std::numeric_limits<float>::quiet_NaN();
      ++stats->no_return_readings;
    } else {
      scan->ranges[static_cast<size_t>(i)] = static_cast<float>(r);
    }
  }
}

void AddScan(ParseState* s, LadarScan scan, const Pose2& laser, const Pose2& robot, double v, double omega) {
  CarmenLog& log = s->log;
  scan.scan_id = static_cast<int64_t>(log.scans.size());
  scan.sensor_offset = Between(robot, laser);
  if (!log.scans.empty() && scan.utime < log.scans.back().utime) ++log.stats.scan_time_reversals;
  OdometryReading odo;
  odo.utime = scan.utime;
  odo.seq = scan.scan_id;
  odo.pose = robot;
  odo.v = v;
  odo.omega = omega;
  log.scans.push_back(std::move(scan));
  log.scan_odometry.push_back(odo);
}

void ParseFlaser(ParseState* s, const LineParser& p) {
  p.ExpectAtLeast(2, "FLASER n ...");
  const int n = p.Count(1, "number of readings");
  p.ExpectFields(static_cast<size_t>(n) + 11, "FLASER n, n ranges, laser x y theta, odometry x y theta, "
                                              "ipc_timestamp host logger_timestamp");
  const CarmenReadOptions& o = *s->options;
  LadarScan scan;
  scan.utime = p.IpcUtime();
  scan.sensor_id = "FLASER";
  scan.start_angle = -kPi / 2.0;
  scan.angle_step = FlaserAngleStep(n);
  scan.min_range = o.min_range;
  scan.max_range = s->front_laser_max > 0.0 ? std::min(s->front_laser_max, o.max_range) : o.max_range;
  FillRanges(p, 2, n, &scan, &s->log.stats);
  const size_t k = 2 + static_cast<size_t>(n);
  const Pose2 laser(p.Double(k, "laser x"), p.Double(k + 1, "laser y"), NormalizeAngle(p.Double(k + 2, "laser theta")));
  const Pose2 robot(p.Double(k + 3, "odometry x"), p.Double(k + 4, "odometry y"),
                    NormalizeAngle(p.Double(k + 5, "odometry theta")));
  ++s->log.stats.flaser_lines;
  AddScan(s, std::move(scan), laser, robot, 0.0, 0.0);
}

void ParseRobotLaser1(ParseState* s, const LineParser& p) {
  const std::string layout =
      "ROBOTLASER1 type start_angle fov angular_res max_range accuracy remission_mode n, n ranges, m, "
      "m remissions, laser x y theta, robot x y theta, tv rv forward_safety side_safety turn_axis, "
      "ipc_timestamp host logger_timestamp";
  p.ExpectAtLeast(9, layout);
  const int n = p.Count(8, "number of readings");
  p.ExpectAtLeast(10 + static_cast<size_t>(n), layout);
  const int m = p.Count(9 + static_cast<size_t>(n), "number of remissions");
  p.ExpectFields(static_cast<size_t>(n) + static_cast<size_t>(m) + 24, layout);
  const CarmenReadOptions& o = *s->options;
  LadarScan scan;
  scan.utime = p.IpcUtime();
  scan.sensor_id = "ROBOTLASER1";
  scan.start_angle = p.Double(2, "start angle");
  const double step = p.Double(4, "angular resolution");
  if (!(step > 0.0) || step > kPi) p.Fail("angular resolution " + std::to_string(step) + " rad is not in (0, pi]");
  scan.angle_step = step;
  const double line_max = p.Double(5, "maximum range");
  if (!(line_max > 0.0)) p.Fail("maximum range " + std::to_string(line_max) + " m is not positive");
  scan.min_range = o.min_range;
  scan.max_range = std::min(line_max, o.max_range);
  FillRanges(p, 9, n, &scan, &s->log.stats);
  if (m > 0) {
    // Remissions are kept as intensities only when there is one per range.
    if (m == n) {
      scan.intensities.resize(static_cast<size_t>(m));
      for (int i = 0; i < m; ++i)
        scan.intensities[static_cast<size_t>(i)] =
            static_cast<float>(p.Double(10 + static_cast<size_t>(n + i), "remission"));
    }
  }
  const size_t k = 10 + static_cast<size_t>(n) + static_cast<size_t>(m);
  const Pose2 laser(p.Double(k, "laser x"), p.Double(k + 1, "laser y"), NormalizeAngle(p.Double(k + 2, "laser theta")));
  const Pose2 robot(p.Double(k + 3, "robot x"), p.Double(k + 4, "robot y"), NormalizeAngle(p.Double(k + 5, "robot theta")));
  const double tv = p.Double(k + 6, "tv");
  const double rv = p.Double(k + 7, "rv");
  ++s->log.stats.robotlaser1_lines;
  AddScan(s, std::move(scan), laser, robot, tv, rv);
}

void ParseOdom(ParseState* s, const LineParser& p) {
  p.ExpectFields(10, "ODOM x y theta tv rv accel ipc_timestamp host logger_timestamp");
  OdometryReading odo;
  odo.utime = p.IpcUtime();
  odo.pose = Pose2(p.Double(1, "x"), p.Double(2, "y"), NormalizeAngle(p.Double(3, "theta")));
  odo.v = p.Double(4, "tv");
  odo.omega = p.Double(5, "rv");
  CarmenLog& log = s->log;
  odo.seq = static_cast<int64_t>(log.odometry.size());
  if (!log.odometry.empty() && odo.utime < log.odometry.back().utime) ++log.stats.odometry_time_reversals;
  log.odometry.push_back(odo);
  ++log.stats.odom_lines;
}

void ParseParam(ParseState* s, const LineParser& p, const std::vector<std::string_view>& f) {
  p.ExpectAtLeast(3, "PARAM name value ...");
  ++s->log.stats.param_lines;
  if (f[1] == "robot_front_laser_max") {
    const double v = p.Double(2, "robot_front_laser_max");
    if (!(v > 0.0)) p.Fail("robot_front_laser_max " + Excerpt(f[2]) + " m is not positive");
    s->front_laser_max = v;
  }
}

void MakeMonotonic(CarmenLog* log) {
  auto fix = [](auto* readings) {
    for (size_t i = 1; i < readings->size(); ++i)
      if ((*readings)[i].utime <= (*readings)[i - 1].utime) (*readings)[i].utime = (*readings)[i - 1].utime + 1;
  };
  fix(&log->scans);
  fix(&log->odometry);
  for (size_t i = 0; i < log->scans.size(); ++i) log->scan_odometry[i].utime = log->scans[i].utime;
}

}  // namespace

namespace {

// Other spellings of a number ("1.08499e-42" appears in intel-corrected's ODOM lines):
// through a double, rounded to the microsecond.
bool ParseTimestampAsDouble(const std::string& text, int64_t* utime) {
  double v = 0.0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size() || !std::isfinite(v) || std::abs(v) > 1e12)
    return false;
  *utime = std::llround(v * 1e6);
  return true;
}

bool ParseDecimalTimestamp(const std::string& text, int64_t* utime) {
  const size_t dot = text.find('.');
  const std::string_view whole = std::string_view(text).substr(0, dot);
  const std::string_view frac = dot == std::string::npos ? std::string_view() : std::string_view(text).substr(dot + 1);
  if (whole.empty() || frac.size() > 6) return false;
  bool negative = false;
  std::string_view digits = whole;
  if (digits.front() == '-') {
    negative = true;
    digits.remove_prefix(1);
  }
  if (digits.empty() || digits.size() > 12) return false;
  int64_t seconds = 0;
  for (char c : digits) {
    if (c < '0' || c > '9') return false;
    seconds = seconds * 10 + (c - '0');
  }
  int64_t micros = 0;
  for (size_t i = 0; i < 6; ++i) {
    int digit = 0;
    if (i < frac.size()) {
      if (frac[i] < '0' || frac[i] > '9') return false;
      digit = frac[i] - '0';
    }
    micros = micros * 10 + digit;
  }
  const int64_t t = seconds * 1000000 + micros;
  *utime = negative ? -t : t;
  return true;
}

}  // namespace

bool ParseCarmenTimestamp(const std::string& text, int64_t* utime) {
  return ParseDecimalTimestamp(text, utime) || ParseTimestampAsDouble(text, utime);
}

int64_t MakeStrictlyIncreasing(std::vector<int64_t>* utimes) {
  int64_t changed = 0;
  for (size_t i = 1; i < utimes->size(); ++i) {
    if ((*utimes)[i] <= (*utimes)[i - 1]) {
      (*utimes)[i] = (*utimes)[i - 1] + 1;
      ++changed;
    }
  }
  return changed;
}

namespace {

void CheckReadOptions(const CarmenReadOptions& options) {
  if (!(options.max_range > 0.0) || !(options.min_range >= 0.0) || options.min_range >= options.max_range)
    throw InputError("CARMEN reader: need 0 <= min_range < max_range, got " + std::to_string(options.min_range) +
                     ", " + std::to_string(options.max_range) + " m");
  if (options.max_line_bytes == 0) throw InputError("CARMEN reader: max_line_bytes must be > 0");
}

// Parses one line at a time, in file order; Finish() gives the log.
class CarmenParser {
 public:
  CarmenParser(const std::string& source_name, const CarmenReadOptions& options) : source_(source_name) {
    CheckReadOptions(options);
    state_.options = &options;
  }

  // `line` without its '\n'.
  void AddLine(std::string_view line) {
    ++line_number_;
    ++state_.log.stats.lines;
    if (line.size() > state_.options->max_line_bytes)
      ThrowLineTooLong(source_, line_number_, state_.options->max_line_bytes);
    SplitFields(line, &fields_);
    if (fields_.empty() || fields_[0].front() == '#') return;
    const LineParser p(source_, line_number_, fields_);
    const std::string_view kind = fields_[0];
    if (kind == "FLASER") {
      ParseFlaser(&state_, p);
    } else if (kind == "ROBOTLASER1") {
      ParseRobotLaser1(&state_, p);
    } else if (kind == "ODOM") {
      ParseOdom(&state_, p);
    } else if (kind == "PARAM") {
      ParseParam(&state_, p, fields_);
    } else {
      ++state_.log.stats.ignored_lines;
    }
  }

  // The number the next line will have (for errors about a line not yet complete).
  int64_t next_line_number() const { return line_number_ + 1; }
  size_t max_line_bytes() const { return state_.options->max_line_bytes; }

  CarmenLog Finish() {
    if (state_.options->monotonic_times) MakeMonotonic(&state_.log);
    return std::move(state_.log);
  }

 private:
  const std::string& source_;
  ParseState state_;
  std::vector<std::string_view> fields_;
  int64_t line_number_ = 0;
};

}  // namespace

CarmenLog ParseCarmenLog(const std::string& text, const std::string& source_name, const CarmenReadOptions& options) {
  CarmenParser parser(source_name, options);
  const std::string_view all(text);
  size_t pos = 0;
  while (pos < all.size()) {
    size_t end = all.find('\n', pos);
    if (end == std::string_view::npos) end = all.size();
    parser.AddLine(all.substr(pos, end - pos));
    pos = end + 1;
  }
  return parser.Finish();
}

CarmenLog ReadCarmenLog(const std::string& path, const CarmenReadOptions& options) {
  CarmenParser parser(path, options);
  const std::unique_ptr<ByteSource> source = OpenMaybeCompressed(path);
  std::vector<char> chunk(kChunkBytes);
  // The start of a line whose '\n' has not arrived yet; never longer than the line limit
  // plus one chunk, so a single endless line cannot exhaust memory.
  std::string partial;
  while (const size_t n = source->Read(chunk.data(), chunk.size())) {
    std::string_view rest(chunk.data(), n);
    for (size_t newline = rest.find('\n'); newline != std::string_view::npos; newline = rest.find('\n')) {
      if (partial.empty()) {
        parser.AddLine(rest.substr(0, newline));
      } else {
        partial.append(rest.substr(0, newline));
        parser.AddLine(partial);
        partial.clear();
      }
      rest.remove_prefix(newline + 1);
    }
    partial.append(rest);
    if (partial.size() > parser.max_line_bytes())
      ThrowLineTooLong(path, parser.next_line_number(), parser.max_line_bytes());
  }
  if (!partial.empty()) parser.AddLine(partial);
  return parser.Finish();
}

}  // namespace minenav
