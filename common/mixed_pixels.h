#pragma once
// Mixed pixels (thesis 2.2: "the laser beam reflected partially from the near object and
// partially from the far one"): where a beam straddles an occluding edge, the ladar reports a
// range between the two surfaces, on neither. Such a reading sits in the scan between two range
// levels, one or two readings wide (the beam is about as wide as the angular step): the
// readings before it continue one surface, those after it the other. Left in, it joins the near
// and the far surface where their gap is under twice the splitter's break distance (under it
// from both), and the mapper makes a contour along the ray (the research mine's 36-48 cm worst
// deviation, mapper/README.md).
//
// The surfaces are judged as they continue: the four readings on each side of the run are
// extrapolated in a straight line (in range) to the run (they must lie on one, within the
// noise factor), and a mixed reading lies between
// the two continuations, off each. A wall seen at a grazing angle climbs from reading to
// reading, but its readings lie on its own continuation, so it is never taken for one.

#include <vector>

namespace minenav {

struct MixedPixelOptions {
  // Readings; the longest run between two surfaces taken for mixed pixels (2: the beam of a
  // mining ladar is one to two angular steps wide, the Typhoon's 3 mrad against 3.07 mrad).
  int max_run = 2;
  // Of the range noise: a mixed reading lies more than this many sigma off each surface's
  // continuation, plus a sigma per reading extrapolated (3: a Gaussian's 99.7 %).
  double noise_factor = 3.0;
};

// True for every reading (index into `ranges`) that is a mixed pixel: a run of at most
// max_run valid readings with four valid readings on each side, each reading between the two
// sides' continuations and off each by more than noise_factor * `range_noise` (m) plus
// `range_noise` per reading extrapolated. `valid` says which readings are returns; the scan's
// two ends are not joined.
std::vector<bool> FindMixedPixels(const std::vector<float>& ranges, const std::vector<bool>& valid,
                                  double range_noise, const MixedPixelOptions& options = {});

}  // namespace minenav
