#include "common/file_io.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "tests/temp_dir.h"

namespace minenav {
namespace {

TEST(FileIoTest, SegmentsRoundTrip) {
  const std::vector<Segment> segs = {{0, 0, 1, 2.5}, {-3.25, 4, 7, 1e-3}};
  const auto back = ParseSegmentsJson(SegmentsToJson(segs), "mem");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_TRUE(back[1].a.isApprox(segs[1].a));
  EXPECT_TRUE(back[1].b.isApprox(segs[1].b));
}

TEST(FileIoTest, SegmentsAllowOtherKeys) {
  const auto s = ParseSegmentsJson(R"({"name": "mine", "segments": [[1,2,3,4]], "seed": 7})", "mem");
  ASSERT_EQ(s.size(), 1u);
}

TEST(FileIoTest, MalformedSegmentsAreNamed) {
  auto message = [](const std::string& text) {
    try {
      ParseSegmentsJson(text, "w.json");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message("{").find("not valid JSON"), std::string::npos);
  EXPECT_NE(message("[]").find("\"segments\""), std::string::npos);
  EXPECT_NE(message(R"({"segments": [[1,2,3]]})").find("segments[0]"), std::string::npos);
  EXPECT_NE(message(R"({"segments": [[1,2,3,4],[1,"a",3,4]]})").find("segments[1]"), std::string::npos);
}

// Issue 16 (fuzz target segments_json): a number beyond a double made nlohmann throw
// out_of_range, which is no InputError: the process ended "failed" (exit 3) without the file.
TEST(FileIoTest, ANumberBeyondADoubleIsABadFileNamed) {
  try {
    ParseSegmentsJson(R"({"segments": [[0, 0, 121e308, 0]]})", "w.json");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("w.json: not valid JSON"), std::string::npos) << e.what();
  }
}

TEST(FileIoTest, PosesCsvRoundTripAndErrors) {
  const std::vector<StampedPose> poses = {{100, {1, 2, 0.5}}, {200, {-1, 3.25, -3.0}}};
  const auto back = ParsePosesCsv(PosesToCsv(poses), "mem");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].utime, 200);
  EXPECT_DOUBLE_EQ(back[1].pose.y, 3.25);
  EXPECT_THROW(ParsePosesCsv("t,x,y,theta\n1,2,3,4\n", "p.csv"), InputError);
  try {
    ParsePosesCsv("utime,x,y,theta\n1,2,3,4\n2,2,x,4\n", "p.csv");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("p.csv:3"), std::string::npos) << e.what();
  }
}

// Issue 18: a poses file says which rows are estimates. Each status survives the round trip, a
// file of the old four columns reads as estimates, and an unknown status names its line.
TEST(FileIoTest, PosesCsvStatusColumn) {
  const std::vector<StampedPose> poses = {{100, {1, 2, 0.5}, PoseStatus::kEstimated},
                                          {200, {2, 2, 0.5}, PoseStatus::kInserted},
                                          {300, {3, 2, 0.5}, PoseStatus::kTracked},
                                          {400, {4, 2, 0.5}, PoseStatus::kNotConverged}};
  const std::string csv = PosesToCsv(poses);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "utime,x,y,theta,status");
  EXPECT_NE(csv.find("\n400,4,2,0.5,not_converged\n"), std::string::npos) << csv;
  const auto back = ParsePosesCsv(csv, "mem");
  ASSERT_EQ(back.size(), 4u);
  for (size_t i = 0; i < poses.size(); ++i) EXPECT_EQ(back[i].status, poses[i].status) << i;
  EXPECT_TRUE(IsEstimate(back[1].status));
  EXPECT_TRUE(IsEstimate(back[2].status));
  EXPECT_FALSE(IsEstimate(back[3].status));

  const auto old = ParsePosesCsv("utime,x,y,theta\n1,2,3,4\n", "old.csv");
  ASSERT_EQ(old.size(), 1u);
  EXPECT_EQ(old[0].status, PoseStatus::kEstimated);
  try {
    ParsePosesCsv("utime,x,y,theta,status\n1,2,3,4,tracked\n2,2,3,4,guessed\n", "p.csv");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("p.csv:3: status 'guessed'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ParsePosesCsv("utime,x,y,theta,status\n1,2,3,4\n", "p.csv"), InputError);
}

TEST(FileIoTest, StationsWithOptionalWorldColumn) {
  auto st = ParseStationsCsv("x,y,theta\n1,2,0.1\n3,4,0.2\n", "s.csv");
  ASSERT_EQ(st.size(), 2u);
  EXPECT_EQ(st[1].world, 0);
  st = ParseStationsCsv("x,y,theta,world\n1,2,0.1,0\n3,4,0.2,1\n", "s.csv");
  EXPECT_EQ(st[1].world, 1);
  EXPECT_THROW(ParseStationsCsv("x,y,theta,world\n1,2,0.1,-1\n", "s.csv"), InputError);
  EXPECT_THROW(ParseStationsCsv("x,y,theta\n1,2\n", "s.csv"), InputError);
  EXPECT_THROW(ParseStationsCsv("", "s.csv"), InputError);
}

TEST(FileIoTest, AtomicWriteLeavesNoTemporary) {
  const testing::TempDir temp("minenav_fileio_test");
  const std::filesystem::path& dir = temp.path();
  const std::string path = (dir / "out.json").string();
  SaveSegmentsJson(path, {{0, 0, 1, 1}});
  EXPECT_EQ(LoadSegmentsJson(path).size(), 1u);
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 1);
  EXPECT_THROW(SaveSegmentsJson((dir / "missing" / "x.json").string(), {}), InputError);
}

// keep_previous: the replaced file stays whole as PATH.prev; durable changes nothing visible.
TEST(FileIoTest, AtomicWriteKeepsThePreviousFileWhenAsked) {
  const testing::TempDir temp("minenav_fileio_prev_test");
  const std::string path = (temp.path() / "state.bin").string();
  const AtomicWriteOptions keep{.durable = true, .keep_previous = true};
  WriteFileAtomically(path, "first", keep);
  EXPECT_EQ(ReadFile(path), "first");
  EXPECT_FALSE(std::filesystem::exists(PreviousFilePath(path)));  // nothing was replaced
  WriteFileAtomically(path, "second", keep);
  WriteFileAtomically(path, "third", keep);
  EXPECT_EQ(ReadFile(path), "third");
  EXPECT_EQ(ReadFile(PreviousFilePath(path)), "second");
  // A plain write leaves the previous file alone (and keeps none).
  WriteFileAtomically(path, "fourth");
  EXPECT_EQ(ReadFile(PreviousFilePath(path)), "second");
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(temp.path())) files += e.is_regular_file();
  EXPECT_EQ(files, 2);  // no temporary left
}

// An output path that is a pipe or a device (--poses-out /dev/null) is written in place, not
// replaced by a file: a run once turned the machine's /dev/null into a CSV. A FIFO stands in
// for the device (a failure here must not break the machine's /dev/null).
TEST(FileIoTest, AnOutputThatIsAPipeIsWrittenNotReplaced) {
  const testing::TempDir temp("minenav_fileio_fifo_test");
  const std::string path = (temp.path() / "poses.fifo").string();
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
  // The reading end first, without blocking, so the writer's open finds a reader.
  const int reader = ::open(path.c_str(), O_RDONLY | O_NONBLOCK);
  ASSERT_GE(reader, 0);
  SavePosesCsv(path, {{5, Pose2(1, 2, 0.5)}});
  char buffer[256] = {};
  const ssize_t n = ::read(reader, buffer, sizeof(buffer) - 1);
  ::close(reader);
  EXPECT_EQ(std::string(buffer, n > 0 ? static_cast<size_t>(n) : 0), PosesToCsv({{5, Pose2(1, 2, 0.5)}}));
  EXPECT_TRUE(std::filesystem::is_fifo(path));
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(temp.path())) files += e.is_regular_file();
  EXPECT_EQ(files, 0);  // no temporary, no file in its place
  // A folder is no output.
  try {
    WriteFileAtomically(temp.path().string(), "x");
    ADD_FAILURE() << "a folder was written";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is a folder"), std::string::npos) << e.what();
  }
}

TEST(FileIoTest, OutputThatIsAnInputIsRefused) {
  const testing::TempDir temp("minenav_fileio_same_test");
  const std::filesystem::path& dir = temp.path();
  const std::string log = (dir / "run.lcm").string();
  WriteFileAtomically(log, "data");
  EXPECT_THROW(CheckOutputIsNotInput("--map-out", log, {log}), InputError);
  // Another spelling of the same file.
  EXPECT_THROW(CheckOutputIsNotInput("--map-out", (dir / "." / "run.lcm").string(), {log}), InputError);
  std::filesystem::create_symlink(log, dir / "link.lcm");
  EXPECT_THROW(CheckOutputIsNotInput("--json-out", (dir / "link.lcm").string(), {"", log}), InputError);
  EXPECT_NO_THROW(CheckOutputIsNotInput("--map-out", (dir / "map.json").string(), {log}));
  EXPECT_NO_THROW(CheckOutputIsNotInput("--map-out", "", {log}));
  EXPECT_EQ(ReadFile(log), "data");
}

}  // namespace
}  // namespace minenav
