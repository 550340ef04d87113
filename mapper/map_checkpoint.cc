#include "mapper/map_checkpoint.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <set>

#include "common/file_io.h"
#include "mapper/contour_map_io.h"

namespace minenav::mapper {

namespace {

constexpr char kMagic[8] = {'M', 'N', 'C', 'L', 'U', 'E', 'C', 'K'};
constexpr uint32_t kVersion = 1;
// m; scan points and the sensor lie within this of the vehicle (no ladar sees farther):
// more is a forged or corrupt checkpoint, like a contour beyond contour_map_io.h's limits.
constexpr double kMaxScanPointRange = 1000.0;

uint64_t Fnv1a(const char* data, size_t size) {
  uint64_t h = 1469598103934665603ull;
  for (size_t i = 0; i < size; ++i) {
    h ^= static_cast<unsigned char>(data[i]);
    h *= 1099511628211ull;
  }
  return h;
}

class Writer {
 public:
  template <typename T>
  void Raw(T v) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &v, sizeof(T));  // the machines we run on are little-endian
    out_.append(bytes, sizeof(T));
  }
  void I32(int32_t v) { Raw(v); }
  void U32(uint32_t v) { Raw(v); }
  void I64(int64_t v) { Raw(v); }
  void F64(double v) { Raw(v); }
  void Bool(bool v) { Raw(static_cast<uint8_t>(v ? 1 : 0)); }
  void Count(size_t n) { U32(static_cast<uint32_t>(n)); }
  void Point(const Eigen::Vector2d& p) {
    F64(p.x());
    F64(p.y());
  }
  void Pose(const Pose2& p) {
    F64(p.x);
    F64(p.y);
    F64(p.theta);
  }
  std::string& str() { return out_; }

 private:
  std::string out_;
};

class Reader {
 public:
  Reader(const std::string& data, size_t begin, size_t end, std::string source)
      : data_(data), pos_(begin), end_(end), source_(std::move(source)) {}

  [[noreturn]] void Fail(const std::string& what) const {
    throw InputError(source_ + ": checkpoint " + what + " (at byte " + std::to_string(pos_) + ")");
  }
  template <typename T>
  T Raw(const char* what) {
    if (end_ - pos_ < sizeof(T)) Fail(std::string("truncated in ") + what);
    T v;
    std::memcpy(&v, data_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  int32_t I32(const char* what) { return Raw<int32_t>(what); }
  int64_t I64(const char* what) { return Raw<int64_t>(what); }
  double F64(const char* what) {
    const double v = Raw<double>(what);
    if (!std::isfinite(v)) Fail(std::string("non-finite number in ") + what);
    return v;
  }
  bool Bool(const char* what) {
    const uint8_t v = Raw<uint8_t>(what);
    if (v > 1) Fail(std::string("bad flag in ") + what);
    return v == 1;
  }
  // A count of items of at least `min_item_bytes` each: larger than what is left = corrupt.
  size_t Count(const char* what, size_t min_item_bytes) {
    const uint32_t n = Raw<uint32_t>(what);
    if (static_cast<uint64_t>(n) * min_item_bytes > end_ - pos_)
      Fail(std::string("count ") + std::to_string(n) + " of " + what + " exceeds the data");
    return n;
  }
  Eigen::Vector2d Point(const char* what) {
    const double x = F64(what);
    return {x, F64(what)};
  }
  Pose2 Pose(const char* what) {
    const double x = F64(what), y = F64(what), theta = F64(what);
    if (std::abs(theta) > 4.0) Fail(std::string("heading out of range in ") + what);
    if (std::abs(x) > kMaxMapCoordinate || std::abs(y) > kMaxMapCoordinate)
      Fail(std::string("position farther than ") + std::to_string(static_cast<int64_t>(kMaxMapCoordinate)) +
           " m from the origin in " + what);
    return {x, y, theta};
  }
  // A point in the vehicle frame: within kMaxScanPointRange of the vehicle.
  Eigen::Vector2d ScanPoint(const char* what) {
    const Eigen::Vector2d p = Point(what);
    if (p.norm() > kMaxScanPointRange)
      Fail(std::string(what) + " " + std::to_string(p.norm()) + " m from the vehicle, more than " +
           std::to_string(static_cast<int>(kMaxScanPointRange)) + " m");
    return p;
  }
  bool AtEnd() const { return pos_ == end_; }

 private:
  const std::string& data_;
  size_t pos_;
  size_t end_;
  std::string source_;
};

}  // namespace

MapperCheckpoint CheckpointOf(const MappingSession& session) {
  MapperCheckpoint c;
  for (const auto& [id, contour] : session.map().contours()) c.contours.push_back(contour);
  c.next_contour_id = session.map().next_id();
  c.scans = session.mapper().scans();
  c.session = session.state();
  return c;
}

std::string EncodeCheckpoint(const MapperCheckpoint& c) {
  Writer w;
  w.I32(c.next_contour_id);
  w.Count(c.contours.size());
  for (const Contour& contour : c.contours) {
    w.I32(contour.id);
    w.Bool(contour.closed);
    w.Count(contour.points.size());
    for (const Eigen::Vector2d& p : contour.points) w.Point(p);
  }
  w.Count(c.scans.size());
  for (const MappedScan& s : c.scans) {
    w.I64(s.scan.utime);
    w.Point(s.scan.sensor_position);
    w.Pose(s.pose);
    w.Bool(s.fixed);
    w.Count(s.scan.partial_scans.size());
    for (const PartialScan& p : s.scan.partial_scans) {
      w.I32(p.first_index);
      w.I32(p.last_index);
      w.Count(p.points.size());
      for (const Eigen::Vector2d& q : p.points) w.Point(q);
    }
  }
  const MappingSessionState& st = c.session;
  w.Bool(st.has_anchor);
  w.Pose(st.anchor_pose);
  w.Pose(st.anchor_odometry);
  w.I32(st.anchor_scan_index);
  w.I32(st.inserts_since_refine);
  w.I64(st.inserted);
  w.I64(st.tracked);
  w.I64(st.refused);
  w.Count(st.poses.size());
  for (const SessionPose& p : st.poses) {
    w.I64(p.utime);
    w.I32(p.scan_index);
    w.Pose(p.pose);
  }
  const std::string payload = std::move(w.str());
  Writer file;
  file.str().append(kMagic, sizeof(kMagic));
  file.U32(kVersion);
  file.Raw(static_cast<uint64_t>(payload.size()));
  file.str() += payload;
  file.Raw(Fnv1a(payload.data(), payload.size()));
  return std::move(file.str());
}

MapperCheckpoint DecodeCheckpoint(const std::string& bytes, const std::string& source) {
  constexpr size_t kHeader = sizeof(kMagic) + 4 + 8;
  if (bytes.size() < kHeader || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0)
    throw InputError(source + ": not a contour-mapper checkpoint (no MNCLUECK magic)");
  Reader header(bytes, sizeof(kMagic), kHeader, source);
  const uint32_t version = header.Raw<uint32_t>("version");
  if (version != kVersion)
    throw InputError(source + ": checkpoint version " + std::to_string(version) + ", this program reads " +
                     std::to_string(kVersion));
  const uint64_t size = header.Raw<uint64_t>("payload size");
  if (bytes.size() - kHeader < 8 || size != bytes.size() - kHeader - 8)
    throw InputError(source + ": checkpoint truncated or padded (payload " + std::to_string(size) + " bytes, file " +
                     std::to_string(bytes.size()) + ")");
  Reader tail(bytes, kHeader + size, bytes.size(), source);
  if (tail.Raw<uint64_t>("hash") != Fnv1a(bytes.data() + kHeader, size))
    throw InputError(source + ": checkpoint corrupt (hash mismatch)");

  Reader r(bytes, kHeader, kHeader + size, source);
  MapperCheckpoint c;
  c.next_contour_id = r.I32("next contour id");
  if (c.next_contour_id < 0) r.Fail("negative next contour id");
  std::set<int> ids;
  const size_t num_contours = r.Count("contours", 9);
  for (size_t i = 0; i < num_contours; ++i) {
    Contour contour;
    contour.id = r.I32("contour id");
    contour.closed = r.Bool("contour closed flag");
    const size_t n = r.Count("contour points", 16);
    if (contour.id < 0 || contour.id >= c.next_contour_id || !ids.insert(contour.id).second)
      r.Fail("contour id " + std::to_string(contour.id) + " duplicate or not below next id " +
             std::to_string(c.next_contour_id));
    if (n < (contour.closed ? 3u : 2u)) r.Fail("contour " + std::to_string(contour.id) + " has too few points");
    contour.points.reserve(n);
    for (size_t k = 0; k < n; ++k) contour.points.push_back(r.Point("contour point"));
    if (const std::string why = CheckContourGeometry(contour.points, contour.closed); !why.empty())
      r.Fail("contour " + std::to_string(contour.id) + ": " + why);
    c.contours.push_back(std::move(contour));
  }
  const size_t num_scans = r.Count("scans", 53);
  for (size_t i = 0; i < num_scans; ++i) {
    MappedScan s;
    s.scan.utime = r.I64("scan utime");
    s.scan.sensor_position = r.ScanPoint("sensor position");
    s.pose = r.Pose("scan pose");
    s.fixed = r.Bool("scan fixed flag");
    const size_t num_partial = r.Count("partial scans", 12);
    for (size_t k = 0; k < num_partial; ++k) {
      PartialScan p;
      p.first_index = r.I32("partial scan index");
      p.last_index = r.I32("partial scan index");
      const size_t n = r.Count("partial scan points", 16);
      p.points.reserve(n);
      for (size_t q = 0; q < n; ++q) p.points.push_back(r.ScanPoint("scan point"));
      s.scan.partial_scans.push_back(std::move(p));
    }
    c.scans.push_back(std::move(s));
  }
  MappingSessionState& st = c.session;
  st.has_anchor = r.Bool("anchor flag");
  st.anchor_pose = r.Pose("anchor pose");
  st.anchor_odometry = r.Pose("anchor odometry");
  st.anchor_scan_index = r.I32("anchor scan index");
  st.inserts_since_refine = r.I32("inserts since refinement");
  st.inserted = r.I64("counter");
  st.tracked = r.I64("counter");
  st.refused = r.I64("counter");
  const auto num_scans_int = static_cast<int>(num_scans);
  if (st.anchor_scan_index < -1 || st.anchor_scan_index >= num_scans_int) r.Fail("anchor scan index out of range");
  if (st.inserts_since_refine < 0 || st.inserted < 0 || st.tracked < 0 || st.refused < 0) r.Fail("negative counter");
  const size_t num_poses = r.Count("pose rows", 36);
  for (size_t i = 0; i < num_poses; ++i) {
    SessionPose p;
    p.utime = r.I64("pose row utime");
    p.scan_index = r.I32("pose row scan index");
    p.pose = r.Pose("pose row");
    if (p.scan_index < -1 || p.scan_index >= num_scans_int) r.Fail("pose row scan index out of range");
    st.poses.push_back(p);
  }
  if (!r.AtEnd()) r.Fail("has trailing bytes");
  return c;
}

void SaveCheckpoint(const std::string& path, const MappingSession& session) {
  WriteFileAtomically(path, EncodeCheckpoint(CheckpointOf(session)), {.durable = true, .keep_previous = true});
}

MapperCheckpoint LoadCheckpoint(const std::string& path) { return DecodeCheckpoint(ReadFile(path), path); }

MapperCheckpoint LoadCheckpointOrPrevious(const std::string& path, std::string* warning) {
  try {
    return LoadCheckpoint(path);
  } catch (const InputError& latest) {
    const std::string previous = PreviousFilePath(path);
    if (!std::filesystem::exists(previous)) throw;
    try {
      MapperCheckpoint c = LoadCheckpoint(previous);
      if (warning)
        *warning = std::string(latest.what()) + ": resuming from the checkpoint before it, " + previous + " (" +
                   std::to_string(c.scans.size()) + " scans)";
      return c;
    } catch (const InputError& before) {
      throw InputError(std::string(latest.what()) + "; and the one before it: " + before.what());
    }
  }
}

MappingSession RestoreSession(const MappingSessionOptions& options, MapperCheckpoint c) {
  ContourMap map(options.mapper.grid_cell_size);
  map.Restore(std::move(c.contours), c.next_contour_id);
  return MappingSession(options, std::move(map), std::move(c.scans), std::move(c.session));
}

}  // namespace minenav::mapper
