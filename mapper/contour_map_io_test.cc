#include "mapper/contour_map_io.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "common/file_io.h"
#include "tests/temp_dir.h"

namespace minenav::mapper {
namespace {

std::string ErrorOf(const std::string& text) {
  try {
    ParseContourMapJson(text, "map.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ContourMapIoTest, RoundTrip) {
  ContourMap map;
  map.Create({{0, 0}, {1.25, 0}, {1.25, 3.0000001}});
  map.Create({{5, 5}, {6, 5}, {6, 6}, {5, 6}}, true);
  const ContourMap back = ParseContourMapJson(ContourMapToJson(map), "mem");
  ASSERT_EQ(back.NumContours(), 2);
  const auto& a = back.contours().begin()->second;
  EXPECT_FALSE(a.closed);
  EXPECT_NEAR(a.points[2].y(), 3.0000001, 1e-9);
  EXPECT_TRUE(std::next(back.contours().begin())->second.closed);
  EXPECT_EQ(back.NumSegments(), map.NumSegments());

  const std::string path = ::minenav::testing::TempPath("mapper_io_test_map.json");
  SaveContourMapJson(path, map);
  EXPECT_EQ(LoadContourMapJson(path).NumSegments(), 6);
  std::remove(path.c_str());
}

TEST(ContourMapIoTest, AcceptsTheContractAsWrittenByOthers) {
  const ContourMap m = ParseContourMapJson(
      R"({"contours": [{"closed": false, "points": [[0, 0], [1, 2]]}], "note": "extra keys are fine"})", "x");
  EXPECT_EQ(m.NumContours(), 1);
  EXPECT_EQ(ParseContourMapJson(R"({"contours": []})", "x").NumContours(), 0);
}

TEST(ContourMapIoTest, RejectsBadInputWithOneLine) {
  const char* cases[] = {
      "not json",
      R"({"segments": []})",
      R"({"contours": [{"closed": "no", "points": [[0,0],[1,1]]}]})",
      R"({"contours": [{"closed": false}]})",
      R"({"contours": [{"closed": false, "points": [[0,0]]}]})",
      R"({"contours": [{"closed": true, "points": [[0,0],[1,1]]}]})",
      R"({"contours": [{"closed": false, "points": [[0,0],[1,"a"]]}]})",
      R"({"contours": [{"closed": false, "points": [[0,0],[1,2,3]]}]})",
      R"({"contours": [{"closed": false, "points": [[0,0],[1e999,2]]}]})",
  };
  for (const char* c : cases) {
    const std::string e = ErrorOf(c);
    EXPECT_FALSE(e.empty()) << c;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    EXPECT_EQ(e.rfind("map.json", 0), 0u) << e;
  }
  EXPECT_NE(ErrorOf(R"({"contours": [{"closed": false, "points": [[0,0]]}]})").find("contour 0"), std::string::npos);
}

// Issue 11, item 7: this 66-byte map made the segment grid visit every 2 m cell of a 20 km
// box (6 GB, 18-39 s, then bad_alloc). It is refused at once, in one line naming what.
TEST(ContourMapIoTest, RefusesAbsurdGeometryQuicklyInOneLine) {
  const std::string twenty_km = R"({"contours": [{"closed": false, "points": [[0, 0], [20000, 20000]]}]})";
  const auto t0 = std::chrono::steady_clock::now();
  const std::string e = ErrorOf(twenty_km);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 0.1);
  EXPECT_EQ(e, "map.json: contour 0: segment 0 is 28284.3 m long, more than the 1000 m a contour segment may be");
  // The closing segment of a closed contour counts too; so do far-off vertices.
  EXPECT_NE(ErrorOf(R"({"contours": [{"closed": true, "points": [[0, 0], [900, 0], [900, 900]]}]})")
                .find("contour 0: segment 2 is 1272.79 m long"),
            std::string::npos);
  EXPECT_NE(ErrorOf(R"({"contours": [{"points": [[0, 0], [1, 0]]}, {"points": [[3e7, 0], [3e7, 1]]}]})")
                .find("contour 1: point 0 (3e+07, 0) is farther than 1e+07 m from the origin"),
            std::string::npos);
  // At the limits: a 1000 m straight rib drawn as one segment, UTM-sized coordinates.
  const ContourMap ok = ParseContourMapJson(
      R"({"contours": [{"points": [[0, 0], [1000, 0]]}, {"points": [[500000, 6000000], [500000.5, 6000000]]}]})", "ok");
  EXPECT_EQ(ok.NumSegments(), 2);
  EXPECT_EQ(CheckContourGeometry({{0, 0}, {3, 4}}, false), "");
}

}  // namespace
}  // namespace minenav::mapper
