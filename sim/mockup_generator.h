#pragma once
// The indoor mine mockup of thesis 2.2 (Figures 5 and 6, Table 1): a corridor about 6 m
// wide in a 20 x 30 m high bay, bounded on one side by the building's concrete wall (with
// ~0.4 m square columns jutting out) and on the other by office partitions. The line
// model holds the partitions and two concrete walls; heavy clutter (people, machines,
// equipment) stands in the bay and is NOT in the model.
//
// What we recover from Table 1: the robot went west along a corridor at y ~ 3.3 m, north
// along one at x ~ 3.5 m, and east along one at y ~ 15.8 m: a U-shaped corridor. Walls are
// placed 3 m either side of those centrelines. Stations are Table 1's surveyed x, y and
// gyro heading (the first heading, "n/a" in the table, is taken as 180 deg: the robot was
// heading west along the first leg).

#include <cstdint>
#include <vector>

#include "common/file_io.h"
#include "common/geometry.h"

namespace minenav {

struct MockupWorld {
  std::vector<Segment> map;      // the surveyed line model (partitions, concrete walls, columns)
  std::vector<Segment> clutter;  // objects in the world but not in the map
  std::vector<Station> stations; // 16 stations of Table 1, in order
  // map + clutter: what the simulated ladar sees.
  std::vector<Segment> World() const;
};

// Clutter placement depends on the seed; the map and stations do not. Clutter keeps at
// least 1 m from the path through the stations.
MockupWorld GenerateIndoorMockup(uint64_t seed = 1);

}  // namespace minenav
