// The path tracker (tracker/README.md, issue 14, "Measured in simulation"): the tracker in a
// closed loop on vehicle_sim's miner (sim/testing/tracker_closed_loop.h): skid-steer kinematics
// and limits, odometry with drift, wheel slip the odometry misses, and a scan every 1, 2 or
// 5 s (1, 0.5, 0.2 Hz) whose pose estimate comes from the LIVE contour mapper
// (--pose_source live, the default: the simulated Typhoon scan of the true world from the
// true pose, mapped with the drifting odometry, inserted every metre or 0.3 rad and tracked
// otherwise, out when its computation is done; the tracker's map is the mapper's) or from a
// noisy model of the truth (--pose_source noisy: 1 cm / 0.11 deg Gaussian noise, --latency
// late, the true world as the map). Paths from the SE(2) planner (clearance 0.15 m): a
// straight entry, a box cut and a slab cut at a face in a generated room-and-pillar mine, a
// multi-point turn at a crossing of 6.5 m entries. Two speed settings: cruise 0.076 m/s (the
// miner) and fast 0.5 m/s. Side by side: plain pure pursuit (tracker.regulated = false:
// cruise everywhere) and ours (regulated). Per cell the medians over the seeds: cross-track
// RMS and max, heading error max, final pose error (true pose against the goal), time,
// turn-in-place corrections, the estimates' error against the truth at their scans and
// their latency; and how many runs ended done, blocked, or in contact with the TRUE walls
// (brute force).
//
//   tracker_bench [--seeds 3] [--pose_source live|noisy] [--scenarios a,b] [--json_out FILE]

#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "common/angle.h"
#include "common/config.h"
#include "sim/testing/tracker_closed_loop.h"

namespace minenav {
namespace {

struct Cell {
  std::vector<double> ct_rms, ct_max, heading_max, final_pos, final_heading, time, corrections;
  std::vector<double> estimate_rms, estimate_max, latency_median, latency_max, cpu;
  int runs = 0, done = 0, blocked = 0, contact = 0, jumps = 0, refused = 0;
  std::vector<std::string> messages;  // how each run ended
};

// m between the survey's scans along the path before each run (the live mapper's map).
constexpr double kSurveySpacing = 8.0;

std::vector<std::string> Split(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

int Run(int argc, char** argv) {
  int seeds = 3;
  std::string json_out, pose_source = "live", scenarios, speeds = "0.076,0.5", rates = "1,0.5,0.2";
  double latency = 0.3;
  ConfigSchema schema("tracker_bench", "The path tracker in a closed loop on the simulated miner.");
  schema.AddInt("seeds", &seeds, "runs per cell (noise seeds 1..n)", 1, 100);
  schema.AddString("pose_source", &pose_source,
                   "live = the contour mapper on simulated scans; noisy = the truth plus Gaussian noise",
                   {"live", "noisy"});
  schema.AddDouble("latency", &latency, "s", "delay of each pose estimate after its scan (noisy only)", 0.0, 10.0);
  schema.AddString("scenarios", &scenarios, "comma-separated maneuvers ('' = all)");
  schema.AddString("speeds", &speeds, "comma-separated cruise speeds, m/s (above 0.1: the fast vehicle)");
  schema.AddString("rates", &rates, "comma-separated scan (pose) rates, Hz");
  schema.AddString("json_out", &json_out, "write the results as JSON to this file ('' = none)");
  if (schema.Parse(argc, argv) == ParseOutcome::kExit) return 0;
  const bool live = pose_source == "live";
  const std::vector<std::string> names = scenarios.empty() ? testing::ScenarioNames() : Split(scenarios);
  std::vector<double> speed_list, rate_list;
  for (const std::string& v : Split(speeds)) speed_list.push_back(std::stod(v));
  for (const std::string& v : Split(rates)) rate_list.push_back(std::stod(v));

  const Footprint miner = Footprint::Rectangle(3.3, 10.0);
  nlohmann::json rows = nlohmann::json::array();
  std::printf("pose source: %s\n", live ? "the live contour mapper (Typhoon scans, insert 1 m / 0.3 rad)"
                                             : "noisy truth (1 cm, 0.11 deg)");
  std::printf("%-18s %-6s %-5s %-9s | %6s %6s %6s %6s %6s %7s %5s | %5s %5s %5s | %s\n", "scenario", "speed", "Hz",
              "tracker", "ctRMS", "ctMax", "hdMax", "endPos", "endHd", "time", "corr", "estE", "lat", "cpu",
              "done/blocked/contact of runs");
  std::printf("%-18s %-6s %-5s %-9s | %6s %6s %6s %6s %6s %7s %5s | %5s %5s %5s |\n", "", "m/s", "", "", "cm", "cm", "deg",
              "cm", "deg", "s", "", "cm", "s", "s");
  for (const std::string& name : names) {
    const testing::TrackingScenario s = testing::MakeScenario(name, 0.15);
    if (!s.error.empty()) throw std::runtime_error(s.error);
    for (const double speed : speed_list) {
      for (const double rate : rate_list) {
        for (const bool regulated : {false, true}) {
          Cell c;
          for (int seed = 1; seed <= seeds; ++seed) {
            testing::ClosedLoopOptions o;
            o.pose_source = live ? testing::PoseSource::kLiveMapper : testing::PoseSource::kNoisyTruth;
            if (live) o.survey = testing::SurveyPoses(s.path, kSurveySpacing);
            o.seed = static_cast<uint64_t>(seed);
            o.pose_rate = rate;
            o.pose_latency = latency;
            o.tracker.regulated = regulated;
            o.tracker.cruise_speed = speed;
            if (speed > 0.1) {
              // The fast setting: the vehicle's limits scaled up with the speed.
              o.vehicle.max_forward_speed = o.vehicle.max_reverse_speed = speed;
              o.vehicle.max_turn_in_place_rate = 0.2;
              o.vehicle.max_acceleration = 0.25;
              o.vehicle.max_deceleration = 0.5;
              o.vehicle.max_yaw_acceleration = 0.2;
              o.tracker.turn_rate = 0.2;
              o.tracker.deceleration = o.vehicle.max_deceleration;
            }
            const double cpu0 = bench::Now();
            const testing::ClosedLoopResult r = testing::RunClosedLoop(s.world, s.world, s.path, miner, o);
            c.cpu.push_back(bench::Now() - cpu0);
            ++c.runs;
            c.refused += r.scans_refused;
            c.estimate_rms.push_back(100 * r.estimate_error_rms);
            c.estimate_max.push_back(100 * r.estimate_error_max);
            c.latency_median.push_back(r.latency_median);
            c.latency_max.push_back(r.latency_max);
            c.done += r.state == TrackState::kDone;
            c.blocked += r.state == TrackState::kBlocked;
            c.contact += r.contact;
            c.jumps += r.jumps;
            c.ct_rms.push_back(100 * r.cross_track_rms);
            c.ct_max.push_back(100 * r.cross_track_max);
            c.heading_max.push_back(RadToDeg(r.heading_max));
            c.final_pos.push_back(100 * r.final_position_error);
            c.final_heading.push_back(RadToDeg(r.final_heading_error));
            c.time.push_back(r.time);
            c.corrections.push_back(r.corrections);
            c.messages.push_back(r.message);
          }
          const char* mode = regulated ? "regulated" : "plain";
          std::printf("%-18s %-6.3f %-5.1f %-9s | %6.2f %6.2f %6.2f %6.2f %6.2f %7.1f %5.0f | %5.2f %5.2f %5.0f | %d/%d/%d of %d\n",
                      name.c_str(), speed, rate, mode, bench::Median(c.ct_rms), bench::Median(c.ct_max),
                      bench::Median(c.heading_max), bench::Median(c.final_pos), bench::Median(c.final_heading),
                      bench::Median(c.time), bench::Median(c.corrections), bench::Median(c.estimate_rms),
                      bench::Median(c.latency_median), bench::Median(c.cpu), c.done, c.blocked, c.contact, c.runs);
          rows.push_back({{"scenario", name}, {"pose_source", pose_source}, {"speed", speed}, {"pose_rate", rate},
                          {"tracker", mode},
                          {"path_length_m", s.path.Length()}, {"reversals", s.path.Reversals()},
                          {"cross_track_rms_cm", c.ct_rms}, {"cross_track_max_cm", c.ct_max},
                          {"heading_max_deg", c.heading_max}, {"final_position_cm", c.final_pos},
                          {"final_heading_deg", c.final_heading}, {"time_s", c.time},
                          {"corrections", c.corrections}, {"runs", c.runs}, {"done", c.done},
                          {"blocked", c.blocked}, {"contact", c.contact}, {"jumps_reported", c.jumps},
                          {"estimate_error_rms_cm", c.estimate_rms}, {"estimate_error_max_cm", c.estimate_max},
                          {"latency_median_s", c.latency_median}, {"latency_max_s", c.latency_max},
                          {"scans_refused", c.refused}, {"cpu_s", c.cpu}, {"messages", c.messages}});
          std::fflush(stdout);
        }
      }
    }
  }
  bench::WriteJson(json_out, {{"bench", "tracker_bench"}, {"seeds", seeds}, {"pose_source", pose_source},
                              {"latency_s", latency}, {"rows", rows}});
  return 0;
}

}  // namespace
}  // namespace minenav

int main(int argc, char** argv) { return minenav::bench::RunBenchMain("tracker_bench", minenav::Run, argc, argv); }
