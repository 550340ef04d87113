// The task planner (planner/README.md, "Task planner"): surveys of generated mines station by
// station until the planner says COMPLETE (stations, metres driven, explored area against the
// true free area, time per decision), and the plans to advance every entry at the mine's
// boundary (how many are planned, the cut widths, time per plan). Prints two tables and
// writes JSON (--json_out); --svg_out PREFIX writes the README's pictures.
//
//   task_planner_bench [--seeds N] [--range M] [--only survey|advance] [--svg_out PREFIX] [--json_out FILE]

#include <cstdio>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "common/angle.h"
#include "common/config.h"
#include "common/file_io.h"
#include "planner/advance_planner.h"
#include "planner/task_plan_svg.h"
#include "sim/testing/survey_exploration.h"
#include "sim/mine_generator.h"

namespace minenav {
namespace {

struct SurveyScenario {
  std::string name;
  int rows, cols;
  double room_width;
  Footprint footprint;
};

std::string Status(PlanStatus s) { return ToString(s); }

int Run(int argc, char** argv) {
  int seeds = 2;
  double range = 20.0;
  std::string only, svg_out, json_out;
  int svg_step = 3;
  std::string svg_all, scenario_filter;
  int first_seed = 1;
  bool verbose = false;
  ConfigSchema schema("task_planner_bench", "Surveys of generated mines and plans to advance their entries.");
  schema.AddInt("seeds", &seeds, "mines per scenario (generator seeds 1..n)", 1, 100);
  schema.AddDouble("range", &range, "m", "the ladar's range (the scans and the planner's prediction)", 5.0, 100.0);
  schema.AddString("only", &only, "survey or advance ('' = both)");
  schema.AddString("svg_out", &svg_out,
                   "write PREFIX_survey.svg (a decision of the first survey) and PREFIX_advance.svg");
  schema.AddInt("svg_step", &svg_step, "the decision of the first survey drawn by --svg_out", 1, 1000);
  schema.AddString("svg_all", &svg_all,
                   "write every decision of every survey as PREFIX_<scenario>_<seed>_<n>.svg (debugging)");
  schema.AddString("scenario", &scenario_filter, "only the survey scenarios whose name contains this");
  schema.AddInt("first_seed", &first_seed, "the first generator seed", 1, 1000000);
  schema.AddBool("verbose", &verbose, "print every decision (time, plans, expansions, reason)");
  schema.AddString("json_out", &json_out, "write the results as JSON to this file ('' = none)");
  if (schema.Parse(argc, argv) == ParseOutcome::kExit) return 0;
  nlohmann::json survey_rows = nlohmann::json::array(), advance_rows = nlohmann::json::array();
  const Footprint carrier = Footprint::Rectangle(1.2, 2.0), miner = Footprint::Rectangle(3.3, 10.0);

  if (only.empty() || only == "survey") {
    const std::vector<SurveyScenario> scenarios = {{"1x2 6 m carrier", 1, 2, 6.0, carrier},
                                                   {"2x3 6 m carrier", 2, 3, 6.0, carrier},
                                                   {"2x3 6.5 m miner", 2, 3, 6.5, miner},
                                                   {"2x3 6 m miner", 2, 3, 6.0, miner}};
    std::printf("Surveys (range %.0f m): station -> scan at the true pose -> contour mapper -> next station\n", range);
    std::printf("%-17s %4s | %8s %7s %8s %8s %7s %7s %7s | %-9s %s\n", "scenario", "seed", "stations", "driven",
                "explored", "true", "cover", "dec.med", "dec.max", "end", "why it ended");
    std::printf("%-17s %4s | %8s %7s %8s %8s %7s %7s %7s |\n", "", "", "", "m", "m^2", "m^2", "%", "ms", "ms");
    for (const SurveyScenario& sc : scenarios) {
      if (sc.name.find(scenario_filter) == std::string::npos) continue;
      for (int seed = first_seed; seed < first_seed + seeds; ++seed) {
        MineOptions mine;
        mine.pillar_rows = sc.rows;
        mine.pillar_cols = sc.cols;
        mine.room_width = sc.room_width;
        mine.seed = static_cast<uint64_t>(seed);
        testing::SurveyExplorationOptions o;
        o.footprint = sc.footprint;
        // The start: the south-west corner's crossing for the carrier; the miner along the
        // south entry (it cannot stand across a 6 m entry).
        o.start = Pose2(sc.name.find("miner") != std::string::npos ? 8.0 : 3.0, 0.5 * sc.room_width, 0.0);
        o.inside = o.start.translation();
        o.sensor_range = range;
        o.survey.sensor_range = range;
        o.max_stations = 60;
        const testing::SurveyExplorationResult r = testing::ExploreBySurvey(
            GenerateRoomAndPillarMine(mine), o,
            [&](const testing::SurveyStep& step, const testing::SurveySimulation& sim) {
              if (verbose)
                std::printf("  decision %d: %.1f ms, %d plans, %lld expansions, %zu candidates: %s\n", step.index,
                            1e3 * step.seconds, step.decision.plans, static_cast<long long>(step.decision.expansions),
                            step.decision.candidates.size(), step.decision.plan.reason.c_str());
              if (!svg_all.empty()) {
                std::string tag = sc.name;
                for (char& c : tag) c = c == ' ' ? '_' : c;
                SvgScene scene =
                    SurveyScene(step.map, sc.footprint, step.request, step.decision,
                                sc.name + " seed " + std::to_string(seed) + " decision " + std::to_string(step.index));
                scene.lines.insert(scene.lines.begin(), SvgLineLayer{"true walls", "#cccccc", 4.0, sim.truth(), {}});
                WriteFileAtomically(
                    svg_all + "_" + tag + "_" + std::to_string(seed) + "_" + std::to_string(step.index) + ".svg",
                    RenderSvg(scene));
              }
              if (svg_out.empty() || seed != 1 || &sc != &scenarios.front() || step.index != svg_step) return;
              SvgScene scene = SurveyScene(step.map, sc.footprint, step.request, step.decision,
                                           "survey of a 1 x 2 pillar mine: decision " + std::to_string(step.index));
              scene.lines.insert(scene.lines.begin(), SvgLineLayer{"true walls", "#cccccc", 4.0, sim.truth(), {}});
              WriteFileAtomically(svg_out + "_survey.svg", RenderSvg(scene));
            });
        std::printf("%-17s %4d | %8d %7.0f %8.0f %8.0f %7.1f %7.1f %7.1f | %-9s %.90s\n", sc.name.c_str(), seed,
                    r.stations, r.path_length, r.known_free_m2, r.true_free_m2, 100.0 * r.Coverage(),
                    bench::Median(r.decision_ms), bench::Max(r.decision_ms), Status(r.final_status).c_str(),
                    r.final_reason.c_str());
        std::fflush(stdout);
        survey_rows.push_back({{"scenario", sc.name},
                               {"seed", seed},
                               {"stations", r.stations},
                               {"driven_m", r.path_length},
                               {"explored_m2", r.known_free_m2},
                               {"true_free_m2", r.true_free_m2},
                               {"known_not_free_m2", r.known_not_free_m2},
                               {"coverage", r.Coverage()},
                               {"decision_ms", r.decision_ms},
                               {"status", Status(r.final_status)},
                               {"reason", r.final_reason},
                               {"refused_scans", r.refused_scans.size()}});
      }
    }
  }

  if (only.empty() || only == "advance") {
    std::printf("\nAdvancing every entry at the east boundary (the miner 3.3 x 10 m, 1 m deep, clearance 0.1 m)\n");
    std::printf("%-6s %4s %5s | %-6s %5s %7s %8s %8s %8s | %s\n", "rooms", "seed", "entry", "status", "slabs", "cut",
                "maneuv.", "time", "", "reason");
    std::printf("%-6s %4s %5s | %-6s %5s %7s %8s %8s %8s |\n", "m", "", "", "", "", "m", "m", "ms", "");
    std::vector<double> ms_all;
    int planned = 0, total = 0;
    for (const double width : {6.0, 6.5, 7.0}) {
      for (int seed = 1; seed <= seeds; ++seed) {
        MineOptions mine;
        mine.room_width = width;
        mine.seed = static_cast<uint64_t>(seed);
        const std::vector<Segment> world = GenerateRoomAndPillarMine(mine);
        const TaskMap map = TaskMapFromSegments(world);
        const Eigen::Vector2d panel = MinePanelSize(mine);
        const double pitch = mine.pillar_size + mine.room_width;
        for (int entry = 0; entry <= mine.pillar_rows; ++entry) {
          const double y = 0.5 * mine.room_width + entry * pitch;
          AdvanceRequest request;
          request.vehicle = Pose2(panel.x() - mine.room_width - 0.5 * mine.pillar_size, y, 0.0);
          request.face_hint = Eigen::Vector2d(panel.x() - 4.0, y);
          request.direction = 0.0;
          request.depth = 1.0;
          request.clearance = 0.1;
          const double t0 = bench::Now();
          const AdvanceResult r = PlanAdvance(map, miner, request, {}, {});
          const double ms = 1e3 * (bench::Now() - t0);
          ms_all.push_back(ms);
          ++total;
          int slabs = 0;
          double cut = 0.0, driven = 0.0;
          for (const Task& t : r.plan.tasks) {
            slabs += t.kind == TaskKind::kSlabCut;
            cut += t.width;
          }
          for (const ManeuverCheck& m : r.maneuvers) driven += m.result.path.Length();
          planned += r.plan.status == PlanStatus::kOk;
          std::printf("%-6.1f %4d %5d | %-6s %5d %7.2f %8.1f %8.1f %8s | %.100s\n", width, seed, entry,
                      Status(r.plan.status).c_str(), slabs, cut, driven, ms, "", r.plan.reason.c_str());
          std::fflush(stdout);
          if (!svg_out.empty() && width == 6.0 && seed == 1 && entry == 1) {
            SvgScene scene = AdvanceScene(map, miner, request, r, "advancing the middle entry of a 2 x 3 pillar mine");
            WriteFileAtomically(svg_out + "_advance.svg", RenderSvg(scene));
          }
          advance_rows.push_back({{"room_width", width},
                                  {"seed", seed},
                                  {"entry", entry},
                                  {"status", Status(r.plan.status)},
                                  {"slabs", slabs},
                                  {"cut_width_m", cut},
                                  {"maneuvers_m", driven},
                                  {"ms", ms},
                                  {"reason", r.plan.reason}});
        }
      }
    }
    std::printf("planned %d of %d; time per plan median %.1f ms, max %.1f ms (thread CPU)\n", planned, total,
                bench::Median(ms_all), bench::Max(ms_all));
  }
  bench::WriteJson(json_out, {{"bench", "task_planner_bench"},
                              {"seeds", seeds},
                              {"range_m", range},
                              {"surveys", survey_rows},
                              {"advances", advance_rows}});
  return 0;
}

}  // namespace
}  // namespace minenav

int main(int argc, char** argv) { return minenav::bench::RunBenchMain("task_planner_bench", minenav::Run, argc, argv); }
