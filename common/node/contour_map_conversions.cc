#include "common/node/contour_map_conversions.h"

#include <zlib.h>

#include <cmath>
#include <string>

#include "common/file_io.h"
#include "common/node/conversions.h"

namespace minenav {

namespace {

contour_map_t Plain(const ContourMapMessage& map) {
  contour_map_t m{};
  m.utime = map.utime;
  m.version = map.version;
  m.num_scans = map.num_scans;
  m.encoding = contour_map_t::ENCODING_PLAIN;
  m.uncompressed_size = 0;
  m.payload_size = 0;
  for (const ContourPolyline& c : map.contours) {
    contour_t t{};
    t.id = c.id;
    t.closed = c.closed;
    t.num_points = static_cast<int32_t>(c.points.size());
    for (const Eigen::Vector2d& p : c.points) {
      t.x.push_back(static_cast<float>(p.x()));
      t.y.push_back(static_cast<float>(p.y()));
    }
    m.contours.push_back(std::move(t));
  }
  m.num_contours = static_cast<int32_t>(m.contours.size());
  return m;
}

}  // namespace

contour_map_t ContourMapToLcm(const ContourMapMessage& map, int compress_above) {
  contour_map_t plain = Plain(map);
  if (plain.getEncodedSize() <= compress_above) return plain;
  const std::vector<uint8_t> raw = EncodeMessage(plain);
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::vector<uint8_t> packed(size);
  if (compress2(packed.data(), &size, raw.data(), static_cast<uLong>(raw.size()), Z_BEST_SPEED) != Z_OK)
    return plain;  // cannot happen with a large enough buffer; plain still decodes
  packed.resize(size);
  contour_map_t m{};
  m.utime = map.utime;
  m.version = map.version;
  m.num_scans = map.num_scans;
  m.num_contours = 0;
  m.encoding = contour_map_t::ENCODING_ZLIB;
  m.uncompressed_size = static_cast<int32_t>(raw.size());
  m.payload_size = static_cast<int32_t>(packed.size());
  m.payload = std::move(packed);
  return m;
}

ContourMapMessage ContourMapFromLcm(const contour_map_t& m) {
  if (m.encoding == contour_map_t::ENCODING_ZLIB) {
    // zlib's deflate cannot shrink data by more than about 1032:1, so a larger claimed
    // size is a lie (a 75-byte packet must not make us allocate 256 MB).
    const int64_t most_inflated = int64_t{1032} * static_cast<int64_t>(m.payload.size()) + 64;
    if (m.uncompressed_size <= 0 || m.uncompressed_size > kMaxUncompressedContourMap ||
        m.uncompressed_size > most_inflated)
      throw InputError("contour map: bad uncompressed_size " + std::to_string(m.uncompressed_size) + " for " +
                       std::to_string(m.payload.size()) + " compressed bytes");
    std::vector<uint8_t> raw(static_cast<size_t>(m.uncompressed_size));
    uLongf size = static_cast<uLongf>(raw.size());
    if (uncompress(raw.data(), &size, m.payload.data(), static_cast<uLong>(m.payload.size())) != Z_OK ||
        size != raw.size())
      throw InputError("contour map: payload does not inflate to " + std::to_string(m.uncompressed_size) + " bytes");
    contour_map_t inner{};
    std::string error;
    if (!DecodeMessage(raw.data(), static_cast<int>(raw.size()), "CONTOUR_MAP payload", &inner, &error))
      throw InputError(error);
    if (inner.encoding != contour_map_t::ENCODING_PLAIN) throw InputError("contour map: nested compression");
    ContourMapMessage out = ContourMapFromLcm(inner);
    out.utime = m.utime;
    out.version = m.version;
    out.num_scans = m.num_scans;
    return out;
  }
  if (m.encoding != contour_map_t::ENCODING_PLAIN)
    throw InputError("contour map: unknown encoding " + std::to_string(m.encoding));
  ContourMapMessage out;
  out.utime = m.utime;
  out.version = m.version;
  out.num_scans = m.num_scans;
  for (const contour_t& c : m.contours) {
    if (c.x.size() != c.y.size() || c.x.size() != static_cast<size_t>(c.num_points))
      throw InputError("contour map: contour " + std::to_string(c.id) + " has x and y of different sizes");
    if (c.x.size() < (c.closed ? 3u : 2u))
      throw InputError("contour map: contour " + std::to_string(c.id) + " has too few points");
    ContourPolyline p;
    p.id = c.id;
    p.closed = c.closed;
    for (size_t i = 0; i < c.x.size(); ++i) {
      if (!std::isfinite(c.x[i]) || !std::isfinite(c.y[i]))
        throw InputError("contour map: contour " + std::to_string(c.id) + " has a non-finite point");
      p.points.emplace_back(c.x[i], c.y[i]);
    }
    out.contours.push_back(std::move(p));
  }
  return out;
}

}  // namespace minenav
