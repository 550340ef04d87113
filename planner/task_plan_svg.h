#pragma once
// Pictures of the task planner's decisions (README figures, bench/task_planner_bench --svg-out):
//   SurveyScene   the contour map (walls, known free space), the frontiers (open ones red,
//                 dropped ones grey), the candidate stations (blue: could be; grey: rejected),
//                 the intersection candidates (purple), the visited stations, the chosen station
//                 and the path to it with the footprint along it;
//   AdvanceScene  the map, the face and ribs found, every task's pose with the footprint
//                 (moves orange, cuts red, back out green) and the checked maneuvers.
// Scenes, so a caller may add layers (a test adds the true walls) before RenderSvg.

#include <string>

#include "planner/advance_planner.h"
#include "planner/survey_planner.h"
#include "planner/task.h"
#include "planner/task_map.h"
#include "render/svg_render.h"

namespace minenav {

SvgScene SurveyScene(const TaskMap& map, const Footprint& footprint, const SurveyRequest& request,
                     const SurveyDecision& decision, const std::string& title);

SvgScene AdvanceScene(const TaskMap& map, const Footprint& footprint, const AdvanceRequest& request,
                      const AdvanceResult& result, const std::string& title);

}  // namespace minenav
