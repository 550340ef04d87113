#include "mapper/map_checkpoint.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/file_io.h"
#include "mapper/test_world.h"
#include "tests/temp_dir.h"

namespace minenav::mapper {
namespace {

using testing::MakeScan;
using testing::NoisySmallRoomScan;
using testing::ScanSpec;
using testing::SmallRoomWorld;

const std::vector<Pose2> kDrive = {{3, 9, 0.3},   {4.5, 9.1, 0.25}, {5.0, 9.1, 0.2}, {6.5, 9.2, 0.0},
                                   {9, 9.5, -0.5}, {13, 9, 0.5},     {17, 9, 2.0},   {17.5, 2, 1.0}};

MappingSessionOptions Options() {
  MappingSessionOptions o;
  o.insert_min_translation = 1.0;  // the 0.5 m step is tracked: pose rows of both kinds
  o.refine_every_inserts = 3;
  o.mapper.refinement.max_rounds = 2;
  return o;
}

// Odometry: truth with a constant offset (another frame) so the anchor composition matters.
Pose2 Odometry(const Pose2& truth) { return Pose2(1.0, -2.0, 0.1) * truth; }

void ExpectSameState(const MappingSession& a, const MappingSession& b) {
  ASSERT_EQ(a.map().contours().size(), b.map().contours().size());
  EXPECT_EQ(a.map().next_id(), b.map().next_id());
  for (const auto& [id, c] : a.map().contours()) {
    const Contour* other = b.map().Find(id);
    ASSERT_NE(other, nullptr) << id;
    EXPECT_EQ(c.closed, other->closed);
    EXPECT_EQ(c.points, other->points);  // bit for bit
  }
  ASSERT_EQ(a.mapper().scans().size(), b.mapper().scans().size());
  for (size_t i = 0; i < a.mapper().scans().size(); ++i) {
    const MappedScan& s = a.mapper().scans()[i];
    const MappedScan& t = b.mapper().scans()[i];
    EXPECT_EQ(s.pose.x, t.pose.x);
    EXPECT_EQ(s.pose.y, t.pose.y);
    EXPECT_EQ(s.pose.theta, t.pose.theta);
    EXPECT_EQ(s.fixed, t.fixed);
    EXPECT_EQ(s.scan.utime, t.scan.utime);
    EXPECT_EQ(s.scan.sensor_position, t.scan.sensor_position);
    ASSERT_EQ(s.scan.partial_scans.size(), t.scan.partial_scans.size());
    for (size_t k = 0; k < s.scan.partial_scans.size(); ++k) {
      EXPECT_EQ(s.scan.partial_scans[k].points, t.scan.partial_scans[k].points);
      EXPECT_EQ(s.scan.partial_scans[k].first_index, t.scan.partial_scans[k].first_index);
      EXPECT_EQ(s.scan.partial_scans[k].last_index, t.scan.partial_scans[k].last_index);
    }
  }
  const MappingSessionState &x = a.state(), &y = b.state();
  EXPECT_EQ(x.has_anchor, y.has_anchor);
  EXPECT_EQ(x.anchor_pose.x, y.anchor_pose.x);
  EXPECT_EQ(x.anchor_odometry.theta, y.anchor_odometry.theta);
  EXPECT_EQ(x.anchor_scan_index, y.anchor_scan_index);
  EXPECT_EQ(x.inserts_since_refine, y.inserts_since_refine);
  EXPECT_EQ(x.inserted, y.inserted);
  EXPECT_EQ(x.tracked, y.tracked);
  EXPECT_EQ(x.refused, y.refused);
  ASSERT_EQ(x.poses.size(), y.poses.size());
  for (size_t i = 0; i < x.poses.size(); ++i) {
    EXPECT_EQ(x.poses[i].utime, y.poses[i].utime);
    EXPECT_EQ(x.poses[i].scan_index, y.poses[i].scan_index);
    EXPECT_EQ(x.poses[i].pose.y, y.poses[i].pose.y);
  }
}

class MapCheckpointTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = temp_.path();
    for (size_t k = 0; k < 5; ++k) Add(session_, k);
    // A refused scan, so the counter is not zero.
    LadarScan far = MakeScan(testing::Rectangle(100, 100, 104, 103), Pose2(102, 101, 0));
    ASSERT_FALSE(session_.AddScan(far, Pose2(102, 101, 0)).accepted());
  }
  static void Add(MappingSession& s, size_t k) {
    const ScanResult r = s.AddScan(NoisySmallRoomScan(kDrive[k], static_cast<unsigned>(k + 1), static_cast<int64_t>(k + 1) * 1000),
                                   Odometry(kDrive[k]));
    ASSERT_TRUE(r.accepted()) << k << ": " << r.status;
  }
  const ::minenav::testing::TempDir temp_{"map_checkpoint_test"};
  std::filesystem::path dir_;
  MappingSession session_{Options()};
};

TEST_F(MapCheckpointTest, RoundTripIsBitExact) {
  ASSERT_GT(session_.state().tracked, 0);
  ASSERT_GT(session_.state().inserted, 2);
  const std::string path = (dir_ / "ck.bin").string();
  SaveCheckpoint(path, session_);
  const MappingSession restored = RestoreSession(Options(), LoadCheckpoint(path));
  ExpectSameState(session_, restored);
  // Encoding the restored state gives the same bytes.
  EXPECT_EQ(EncodeCheckpoint(CheckpointOf(restored)), ReadFile(path));
}

// A restart resumes with nothing lost: the rest of the drive added to the restored session
// gives the state of the uninterrupted one.
TEST_F(MapCheckpointTest, RestoredSessionContinuesLikeTheUninterruptedOne) {
  MappingSession restored = RestoreSession(Options(), DecodeCheckpoint(EncodeCheckpoint(CheckpointOf(session_)), "mem"));
  for (size_t k = 5; k < kDrive.size(); ++k) {
    Add(session_, k);
    Add(restored, k);
  }
  const auto a = session_.Poses(), b = restored.Poses();
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    // The segment grid is rebuilt in id order rather than in edit order; candidate order
    // may differ, so allow floating-point summation differences, far below a millimetre.
    EXPECT_LT(TranslationDistance(a[i].pose, b[i].pose), 1e-9) << i;
    EXPECT_LT(HeadingDistance(a[i].pose, b[i].pose), 1e-9) << i;
  }
  EXPECT_EQ(session_.map().NumContours(), restored.map().NumContours());
  EXPECT_EQ(session_.map().NumSegments(), restored.map().NumSegments());
}

TEST_F(MapCheckpointTest, DamagedFilesGiveOneLineErrors) {
  const std::string good = EncodeCheckpoint(CheckpointOf(session_));
  auto error_of = [](const std::string& bytes) -> std::string {
    try {
      DecodeCheckpoint(bytes, "ck.bin");
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  auto expect_error = [&](const std::string& bytes, const std::string& words) {
    const std::string e = error_of(bytes);
    EXPECT_NE(e.find(words), std::string::npos) << "'" << e << "' lacks '" << words << "'";
    EXPECT_EQ(e.rfind("ck.bin: ", 0), 0u) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  };
  expect_error("", "not a contour-mapper checkpoint");
  expect_error("{\"contours\": []}", "not a contour-mapper checkpoint");
  // Truncated anywhere: the size in the header no longer matches.
  for (const size_t keep : {size_t{20}, size_t{100}, good.size() / 2, good.size() - 1})
    expect_error(good.substr(0, keep), "truncated");
  // One flipped bit inside the payload.
  std::string flipped = good;
  flipped[good.size() / 2] = static_cast<char>(flipped[good.size() / 2] ^ 0x10);
  expect_error(flipped, "hash mismatch");
  // Another version.
  std::string version = good;
  version[8] = 2;
  expect_error(version, "version 2");
  // Consistent bytes with inconsistent content (hash recomputed by the encoder).
  MapperCheckpoint bad = CheckpointOf(session_);
  bad.contours.push_back(bad.contours.front());
  expect_error(EncodeCheckpoint(bad), "duplicate");
  bad = CheckpointOf(session_);
  bad.session.poses.push_back({1, 99, Pose2()});
  expect_error(EncodeCheckpoint(bad), "scan index out of range");
  bad = CheckpointOf(session_);
  bad.scans[1].pose.x = std::nan("");
  expect_error(EncodeCheckpoint(bad), "non-finite");
  // Forged geometry (issue 11, item 7): a 20 km contour segment, a scan point 5 km away, a
  // pose beyond 10 000 km. Refused before any of it reaches the segment grid.
  bad = CheckpointOf(session_);
  bad.contours.front().points.back() = Eigen::Vector2d(20000, 20000);
  expect_error(EncodeCheckpoint(bad), "contour " + std::to_string(bad.contours.front().id) + ": segment");
  expect_error(EncodeCheckpoint(bad), "m long, more than the 1000 m a contour segment may be");
  bad = CheckpointOf(session_);
  bad.scans[2].scan.partial_scans.front().points.front() = Eigen::Vector2d(3000, 4000);
  expect_error(EncodeCheckpoint(bad), "scan point 5000.000000 m from the vehicle, more than 1000 m");
  bad = CheckpointOf(session_);
  bad.session.poses.back().pose.y = -2e7;
  expect_error(EncodeCheckpoint(bad), "position farther than 10000000 m from the origin in pose row");
  // Nothing was ever partly written: an atomic save over an existing file replaces it whole.
  const std::string path = (dir_ / "ck.bin").string();
  std::ofstream(path) << "old";
  SaveCheckpoint(path, session_);
  EXPECT_EQ(ReadFile(path), good);
  EXPECT_THROW(LoadCheckpoint((dir_ / "missing.bin").string()), InputError);
}

// Issue 16: a checkpoint torn by a power cut (a disk that lied about its flush, a copy cut
// short) is detected and the one before it used; with neither whole, one line names both.
TEST_F(MapCheckpointTest, ATornCheckpointIsDetectedAndTheOneBeforeItUsed) {
  const std::string path = (dir_ / "torn.ckpt").string();
  SaveCheckpoint(path, session_);
  const size_t scans_before = session_.mapper().scans().size();
  for (size_t k = 5; k < kDrive.size(); ++k) Add(session_, k);
  ASSERT_GT(session_.mapper().scans().size(), scans_before);
  SaveCheckpoint(path, session_);
  std::string warning;
  EXPECT_EQ(LoadCheckpointOrPrevious(path, &warning).scans.size(), session_.mapper().scans().size());
  EXPECT_EQ(warning, "");

  // Torn: the second half of the newest file never reached the disk.
  const std::string whole = ReadFile(path);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << whole.substr(0, whole.size() / 2);
  const MapperCheckpoint previous = LoadCheckpointOrPrevious(path, &warning);
  EXPECT_EQ(previous.scans.size(), scans_before);
  EXPECT_NE(warning.find(path + ": "), std::string::npos) << warning;
  EXPECT_NE(warning.find("resuming from the checkpoint before it, " + path + ".prev (" + std::to_string(scans_before) +
                         " scans)"),
            std::string::npos)
      << warning;
  EXPECT_EQ(warning.find('\n'), std::string::npos);

  // Both damaged: an error naming both, nothing invented.
  std::string prev = ReadFile(path + ".prev");
  prev[prev.size() / 2] ^= 0x5a;
  std::ofstream(path + ".prev", std::ios::binary | std::ios::trunc) << prev;
  try {
    LoadCheckpointOrPrevious(path, &warning);
    ADD_FAILURE() << "a torn checkpoint and a corrupt previous one loaded";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path + ": "), std::string::npos) << what;
    EXPECT_NE(what.find("the one before it: " + path + ".prev: "), std::string::npos) << what;
  }
  // Without a previous file the error is the file's own.
  std::filesystem::remove(path + ".prev");
  EXPECT_THROW(LoadCheckpointOrPrevious(path, &warning), InputError);
}

}  // namespace
}  // namespace minenav::mapper
