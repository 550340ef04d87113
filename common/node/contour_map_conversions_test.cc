#include "common/node/contour_map_conversions.h"

#include <gtest/gtest.h>

#include <random>

#include "common/file_io.h"
#include "common/node/conversions.h"

namespace minenav {
namespace {

ContourMapMessage MakeMap(int contours, int points) {
  ContourMapMessage map;
  map.utime = 123;
  map.version = 7;
  map.num_scans = 42;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-50, 50);
  for (int c = 0; c < contours; ++c) {
    ContourPolyline p;
    p.id = 10 + c;
    p.closed = c % 2 == 0;
    for (int k = 0; k < points; ++k) p.points.emplace_back(u(rng), u(rng));
    map.contours.push_back(p);
  }
  return map;
}

// Round trip through bytes, as on the bus.
ContourMapMessage ThroughBytes(const contour_map_t& m) {
  const std::vector<uint8_t> bytes = EncodeMessage(m);
  contour_map_t back{};
  std::string error;
  EXPECT_TRUE(DecodeMessage(bytes.data(), static_cast<int>(bytes.size()), "CONTOUR_MAP", &back, &error)) << error;
  return ContourMapFromLcm(back);
}

void ExpectSame(const ContourMapMessage& a, const ContourMapMessage& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.version, b.version);
  EXPECT_EQ(a.num_scans, b.num_scans);
  ASSERT_EQ(a.contours.size(), b.contours.size());
  for (size_t i = 0; i < a.contours.size(); ++i) {
    EXPECT_EQ(a.contours[i].id, b.contours[i].id);
    EXPECT_EQ(a.contours[i].closed, b.contours[i].closed);
    ASSERT_EQ(a.contours[i].points.size(), b.contours[i].points.size());
    for (size_t k = 0; k < a.contours[i].points.size(); ++k)
      EXPECT_LT((a.contours[i].points[k] - b.contours[i].points[k]).norm(), 1e-5);  // float on the wire
  }
}

TEST(ContourMapConversionsTest, SmallMapsTravelPlain) {
  const ContourMapMessage map = MakeMap(3, 20);
  const contour_map_t m = ContourMapToLcm(map);
  EXPECT_EQ(m.encoding, contour_map_t::ENCODING_PLAIN);
  EXPECT_EQ(m.num_contours, 3);
  ExpectSame(map, ThroughBytes(m));
}

TEST(ContourMapConversionsTest, LargeMapsTravelCompressedAndInflateToTheSameMap) {
  const ContourMapMessage map = MakeMap(40, 200);  // 40 * 200 * 8 bytes = 64 KB plain
  const contour_map_t m = ContourMapToLcm(map);
  EXPECT_EQ(m.encoding, contour_map_t::ENCODING_ZLIB);
  EXPECT_EQ(m.num_contours, 0);
  EXPECT_GT(m.uncompressed_size, kContourMapCompressAbove);
  ExpectSame(map, ThroughBytes(m));
  // A threshold above the size keeps it plain.
  EXPECT_EQ(ContourMapToLcm(map, 1 << 20).encoding, contour_map_t::ENCODING_PLAIN);
}

TEST(ContourMapConversionsTest, BadMessagesAreRejectedInOneLine) {
  contour_map_t m = ContourMapToLcm(MakeMap(40, 200));
  contour_map_t broken = m;
  broken.payload[broken.payload.size() / 2] ^= 0x55;
  broken.payload.resize(broken.payload.size() - 10);
  broken.payload_size = static_cast<int32_t>(broken.payload.size());
  EXPECT_THROW(ContourMapFromLcm(broken), InputError);
  broken = m;
  broken.uncompressed_size = -4;
  EXPECT_THROW(ContourMapFromLcm(broken), InputError);
  contour_map_t plain = ContourMapToLcm(MakeMap(2, 5));
  plain.contours[0].y.pop_back();
  EXPECT_THROW(ContourMapFromLcm(plain), InputError);
  plain = ContourMapToLcm(MakeMap(2, 5));
  plain.contours[1].x[2] = std::nanf("");
  try {
    ContourMapFromLcm(plain);
    ADD_FAILURE() << "accepted a NaN";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("non-finite"), std::string::npos);
  }
  plain = ContourMapToLcm(MakeMap(2, 5));
  plain.encoding = 9;
  EXPECT_THROW(ContourMapFromLcm(plain), InputError);
}

}  // namespace
}  // namespace minenav
