#include "mapper/contour_map_io.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "common/file_io.h"

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

  const std::string path = (std::filesystem::temp_directory_path() / "mapper_io_test_map.json").string();
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

}  // namespace
}  // namespace minenav::mapper
