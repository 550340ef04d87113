#include "common/file_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

namespace minenav {

std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw InputError(path + ": read error");
  return ss.str();
}

void CheckOutputIsNotInput(const std::string& what, const std::string& output,
                           const std::vector<std::string>& inputs) {
  if (output.empty()) return;
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const std::string& input : inputs) {
    if (input.empty()) continue;
    const bool same = output == input || (fs::exists(output, ec) && fs::exists(input, ec) &&
                                          fs::equivalent(output, input, ec));
    const bool same_name = fs::weakly_canonical(output, ec) == fs::weakly_canonical(input, ec);
    if (same || (!ec && same_name))
      throw InputError(what + " " + output + " is an input of this run (" + input +
                       "): refusing to overwrite it");
  }
}

namespace {

// Writes `content` to `fd`, again after EINTR and short writes; the bytes written.
size_t WriteAll(int fd, const std::string& content) {
  size_t written = 0;
  while (written < content.size()) {
    const ssize_t n = ::write(fd, content.data() + written, content.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    written += static_cast<size_t>(n);
  }
  return written;
}

// Writes all of `content` to a new file and, when durable, fsyncs it.
void WriteNewFile(const std::string& path, const std::string& tmp, const std::string& content,
                  const AtomicWriteOptions& o) {
  const int fd =
      ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, static_cast<mode_t>(o.mode >= 0 ? o.mode : 0644));
  if (fd < 0) throw InputError(path + ": cannot open for writing: " + std::strerror(errno));
  // The mode forced past the umask before the content (a key file is never readable by others).
  if (o.mode >= 0 && ::fchmod(fd, static_cast<mode_t>(o.mode)) != 0) {
    ::close(fd);
    std::remove(tmp.c_str());
    throw InputError(path + ": cannot create with mode " + std::to_string(o.mode));
  }
  const size_t written = WriteAll(fd, content);
  const bool ok = written == content.size() && (!o.durable || ::fsync(fd) == 0);
  const int error = errno;
  if (::close(fd) != 0 || !ok) {
    std::remove(tmp.c_str());
    throw InputError(path + ": write failed: " + std::strerror(ok ? errno : error));
  }
}

void SyncFolderOf(const std::string& path) {
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  const int fd = ::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;  // the file itself is synced; a folder we cannot open is not an error
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

std::string PreviousFilePath(const std::string& path) { return path + ".prev"; }

namespace {

// A path that names a device or a pipe (/dev/null, a FIFO, /dev/stdout onto a terminal) is
// written in place: renaming a new file onto it would replace the device itself (a run with
// --poses-out /dev/null once turned the machine's /dev/null into a CSV file).
bool WriteInPlaceIfSpecial(const std::string& path, const std::string& content) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || S_ISREG(st.st_mode)) return false;
  if (S_ISDIR(st.st_mode)) throw InputError(path + ": is a folder, not a file");
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) throw InputError(path + ": cannot open for writing: " + std::strerror(errno));
  const size_t written = WriteAll(fd, content);
  const int error = errno;
  ::close(fd);
  if (written != content.size()) throw InputError(path + ": write failed: " + std::strerror(error));
  return true;
}

}  // namespace

void WriteFileAtomically(const std::string& path, const std::string& content, const AtomicWriteOptions& options) {
  if (WriteInPlaceIfSpecial(path, content)) return;
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  WriteNewFile(path, tmp, content, options);
  if (options.keep_previous && std::filesystem::exists(path)) {
    // PATH stays whole throughout: a crash between these steps leaves PATH (and maybe no .prev).
    const std::string previous = PreviousFilePath(path);
    std::remove(previous.c_str());
    if (::link(path.c_str(), previous.c_str()) != 0) {
      std::error_code ec;
      std::filesystem::copy_file(path, previous, std::filesystem::copy_options::overwrite_existing, ec);
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw InputError(path + ": cannot rename temporary file into place");
  }
  if (options.durable) SyncFolderOf(path);
}

// ---- segments JSON ----

std::vector<Segment> ParseSegmentsJson(const std::string& text, const std::string& source_name) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(source_name + ": not valid JSON (byte " + std::to_string(e.byte) + ")");
  } catch (const nlohmann::json::exception& e) {
    // A number beyond a double ("1e999": out_of_range 406) is no parse_error; found by the
    // segments_json fuzz target (issue 16): it escaped as a runtime failure without the file.
    std::string what = e.what();
    throw InputError(source_name + ": not valid JSON (" + what.substr(0, what.find('\n')) + ")");
  }
  if (!doc.is_object() || !doc.contains("segments"))
    throw InputError(source_name + ": expected an object with key \"segments\"");
  const auto& segs = doc["segments"];
  if (!segs.is_array()) throw InputError(source_name + ": \"segments\" is not an array");
  std::vector<Segment> out;
  out.reserve(segs.size());
  for (size_t i = 0; i < segs.size(); ++i) {
    const auto& s = segs[i];
    const std::string where = source_name + ": segments[" + std::to_string(i) + "]";
    if (!s.is_array() || s.size() != 4) throw InputError(where + " is not [x1, y1, x2, y2]");
    double v[4];
    for (size_t k = 0; k < 4; ++k) {
      if (!s[k].is_number()) throw InputError(where + " has a non-numeric coordinate");
      v[k] = s[k].get<double>();
      if (!std::isfinite(v[k])) throw InputError(where + " has a non-finite coordinate");
    }
    out.emplace_back(v[0], v[1], v[2], v[3]);
  }
  return out;
}

std::vector<Segment> LoadSegmentsJson(const std::string& path) {
  return ParseSegmentsJson(ReadFile(path), path);
}

std::string SegmentsToJson(const std::vector<Segment>& segments) {
  std::ostringstream os;
  os << std::setprecision(10) << "{\"segments\": [";
  for (size_t i = 0; i < segments.size(); ++i) {
    const Segment& s = segments[i];
    os << (i ? ",\n  " : "\n  ") << "[" << s.a.x() << ", " << s.a.y() << ", " << s.b.x() << ", "
       << s.b.y() << "]";
  }
  os << "\n]}\n";
  return os.str();
}

void SaveSegmentsJson(const std::string& path, const std::vector<Segment>& segments) {
  WriteFileAtomically(path, SegmentsToJson(segments));
}

// ---- CSV ----

namespace {

std::vector<std::string> SplitCsvLine(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream ss(line);
  while (std::getline(ss, field, ',')) {
    // trim spaces and a trailing CR
    const auto b = field.find_first_not_of(" \t\r");
    const auto e = field.find_last_not_of(" \t\r");
    out.push_back(b == std::string::npos ? "" : field.substr(b, e - b + 1));
  }
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

double ParseDouble(const std::string& s, const std::string& where) {
  size_t used = 0;
  double v = 0;
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    throw InputError(where + ": '" + s + "' is not a number");
  }
  if (used != s.size()) throw InputError(where + ": '" + s + "' is not a number");
  if (!std::isfinite(v)) throw InputError(where + ": '" + s + "' is not finite");
  return v;
}

int64_t ParseInt64(const std::string& s, const std::string& where) {
  size_t used = 0;
  long long v = 0;
  try {
    v = std::stoll(s, &used);
  } catch (const std::exception&) {
    throw InputError(where + ": '" + s + "' is not an integer");
  }
  if (used != s.size()) throw InputError(where + ": '" + s + "' is not an integer");
  return v;
}

// Calls row(fields, where) for every non-empty line after a header that must match.
template <typename RowFn>
void ForEachCsvRow(const std::string& text, const std::string& source_name,
                   const std::vector<std::vector<std::string>>& allowed_headers, RowFn row) {
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  bool header_seen = false;
  size_t columns = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto fields = SplitCsvLine(line);
    const std::string where = source_name + ":" + std::to_string(line_no);
    if (!header_seen) {
      bool ok = false;
      for (const auto& h : allowed_headers) ok = ok || fields == h;
      if (!ok) {
        std::string expected;
        for (const auto& h : allowed_headers) {
          if (!expected.empty()) expected += " or ";
          for (size_t i = 0; i < h.size(); ++i) expected += (i ? "," : "") + h[i];
        }
        throw InputError(where + ": header is '" + line + "', expected " + expected);
      }
      header_seen = true;
      columns = fields.size();
      continue;
    }
    if (fields.size() != columns)
      throw InputError(where + ": " + std::to_string(fields.size()) + " fields, expected " +
                       std::to_string(columns));
    row(fields, where);
  }
  if (!header_seen) throw InputError(source_name + ": empty file, no header");
}

}  // namespace

const char* PoseStatusName(PoseStatus status) {
  switch (status) {
    case PoseStatus::kEstimated: return "estimated";
    case PoseStatus::kInserted: return "inserted";
    case PoseStatus::kTracked: return "tracked";
    case PoseStatus::kNotConverged: return "not_converged";
  }
  return "estimated";
}

bool IsEstimate(PoseStatus status) { return status != PoseStatus::kNotConverged; }

PoseStatus EstimatorPoseStatus(bool converged) {
  return converged ? PoseStatus::kEstimated : PoseStatus::kNotConverged;
}

namespace {

PoseStatus ParsePoseStatus(const std::string& text, const std::string& where) {
  for (PoseStatus s : {PoseStatus::kEstimated, PoseStatus::kInserted, PoseStatus::kTracked, PoseStatus::kNotConverged})
    if (text == PoseStatusName(s)) return s;
  throw InputError(where + ": status '" + text + "' is not estimated, inserted, tracked or not_converged");
}

}  // namespace

std::vector<StampedPose> ParsePosesCsv(const std::string& text, const std::string& source_name) {
  std::vector<StampedPose> out;
  ForEachCsvRow(text, source_name, {{"utime", "x", "y", "theta"}, {"utime", "x", "y", "theta", "status"}},
                [&](const std::vector<std::string>& f, const std::string& where) {
                  out.push_back({ParseInt64(f[0], where),
                                 Pose2(ParseDouble(f[1], where), ParseDouble(f[2], where),
                                       ParseDouble(f[3], where)),
                                 f.size() > 4 ? ParsePoseStatus(f[4], where) : PoseStatus::kEstimated});
                });
  return out;
}

std::vector<StampedPose> LoadPosesCsv(const std::string& path) { return ParsePosesCsv(ReadFile(path), path); }

std::string PosesToCsv(const std::vector<StampedPose>& poses) {
  std::ostringstream os;
  os << "utime,x,y,theta,status\n" << std::setprecision(10);
  for (const auto& p : poses)
    os << p.utime << "," << p.pose.x << "," << p.pose.y << "," << p.pose.theta << "," << PoseStatusName(p.status)
       << "\n";
  return os.str();
}

void SavePosesCsv(const std::string& path, const std::vector<StampedPose>& poses) {
  WriteFileAtomically(path, PosesToCsv(poses));
}

std::vector<Station> ParseStationsCsv(const std::string& text, const std::string& source_name) {
  std::vector<Station> out;
  ForEachCsvRow(text, source_name, {{"x", "y", "theta"}, {"x", "y", "theta", "world"}},
                [&](const std::vector<std::string>& f, const std::string& where) {
                  Station s;
                  s.pose = Pose2(ParseDouble(f[0], where), ParseDouble(f[1], where), ParseDouble(f[2], where));
                  if (f.size() > 3) {
                    const int64_t w = ParseInt64(f[3], where);
                    if (w < 0 || w > 1000000) throw InputError(where + ": world index " + f[3] + " out of range");
                    s.world = static_cast<int>(w);
                  }
                  out.push_back(s);
                });
  return out;
}

std::vector<Station> LoadStationsCsv(const std::string& path) { return ParseStationsCsv(ReadFile(path), path); }

std::string StationsToCsv(const std::vector<Station>& stations) {
  bool any_world = false;
  for (const auto& s : stations) any_world = any_world || s.world != 0;
  std::ostringstream os;
  os << (any_world ? "x,y,theta,world\n" : "x,y,theta\n") << std::setprecision(10);
  for (const auto& s : stations) {
    os << s.pose.x << "," << s.pose.y << "," << s.pose.theta;
    if (any_world) os << "," << s.world;
    os << "\n";
  }
  return os.str();
}

void SaveStationsCsv(const std::string& path, const std::vector<Station>& stations) {
  WriteFileAtomically(path, StationsToCsv(stations));
}

}  // namespace minenav
