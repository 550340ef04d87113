#pragma once
// A mutable line-segment world for the simulator (DESIGN.md "vehicle_sim": "a world that
// changes when coal is cut"; thesis 5.2 scans a 2D world of line segments, 6.4.1 cuts coal).
//
// Each segment has a stable integer id: ids never change while the segment exists and are
// never reused, so a node can say "remove object 17" and a cutter can say "the face is
// segments 40..47". Every change bumps version(), so a consumer (the ladar's ray-casting
// index) rebuilds only when the world really changed.
//
// Cutting coal: the world is taken as walls between free space and solid (coal, pillars).
// CutRegion(polygon, free_point) makes the polygon free space: wall parts inside it vanish
// and the polygon's edges that run through solid become the new (advanced) face. Which
// side is solid is decided by crossing parity relative to a point known to be free, which
// is exact for worlds made of closed loops (every generator in sim/ makes those).
// ReplaceSegments() is the plain alternative when the caller already knows the new face.

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/geometry.h"

namespace minenav {

// A segment together with its stable id.
struct WorldSegment {
  int id = -1;
  Segment segment;
};

// What a CutRegion call changed.
struct CutResult {
  std::vector<int> removed_ids;  // segments deleted (wholly inside, or split)
  std::vector<int> added_ids;    // leftover pieces of split segments and the new face
  double new_face_length = 0.0;  // m of polygon edge that became wall
};

class World {
 public:
  World() = default;
  explicit World(const std::vector<Segment>& segments);

  // Segments JSON contract of DESIGN.md ({"segments": [[x1, y1, x2, y2], ...]}). Throws
  // InputError (common/file_io.h) with a one-line reason on malformed input.
  static World FromJson(const std::string& text, const std::string& source_name);
  static World Load(const std::string& path);
  // Segments in id order. Ids are not stored: a reloaded world renumbers from 0.
  std::string ToJson() const;
  void Save(const std::string& path) const;

  // Returns the new segment's id.
  int AddSegment(const Segment& segment);
  std::vector<int> AddSegments(const std::vector<Segment>& segments);
  // A closed polygon (an object appearing: a machine, a person, a crib block): one segment
  // per edge, vertices in order. Returns the ids, to remove it again later.
  std::vector<int> AddPolygon(const std::vector<Eigen::Vector2d>& vertices);
  // False (and no change) if the id does not exist.
  bool RemoveSegment(int id);
  // Removes those of `ids` that exist; returns how many did.
  int RemoveSegments(const std::vector<int>& ids);
  // Removes `old_ids` and adds `new_segments` in one change (one version bump): the face
  // `old_ids` advanced to `new_segments`. Returns the new ids.
  std::vector<int> ReplaceSegments(const std::vector<int>& old_ids,
                                   const std::vector<Segment>& new_segments);

  // Makes the inside of `polygon` (simple polygon, vertices in order, either orientation)
  // free space, as when the cutter head removes coal. `free_point` must lie in free space
  // of the current world (e.g. the miner's position behind the cutter). Wall segments are
  // split where they cross the polygon; pieces inside are removed; polygon edge pieces
  // lying in solid become wall. One version bump if anything changed.
  CutResult CutRegion(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& free_point);

  // True if p is on the same side of the walls as free_point (even number of wall
  // crossings between them, counted along rays to +x). Exact for closed-loop worlds.
  bool SameSpace(const Eigen::Vector2d& p, const Eigen::Vector2d& free_point) const;

  bool Contains(int id) const { return segments_.count(id) != 0; }
  std::optional<Segment> Find(int id) const;
  // All segments in increasing id order (the order of the JSON file for a loaded world).
  std::vector<Segment> Segments() const;
  std::vector<WorldSegment> Entries() const;
  std::vector<int> Ids() const;
  size_t size() const { return segments_.size(); }
  bool empty() const { return segments_.empty(); }
  // Increments on every change; starts at 0 for an empty world.
  uint64_t version() const { return version_; }

 private:
  int Insert(const Segment& segment);
  int CrossingParity(const Eigen::Vector2d& p) const;

  std::map<int, Segment> segments_;
  int next_id_ = 0;
  uint64_t version_ = 0;
};

}  // namespace minenav
