// The `fleet` tool as a user runs it (fleet/README.md):
//   - FleetCli: `fleet check` / `fleet run` on bad files (one line naming file, line and key,
//     exit 2; no bus needed), `fleet units`, and the mission's fleet file staying valid;
//   - FleetUnits: the generated units and the deploy/ template pass `systemd-analyze verify`;
//   - FleetRun (inside tests/bus/private_net.sh): tiny child programs (sleep, a script that
//     exits 1 at once, one that ignores SIGINT) and real fleet processes (vehicle_sim,
//     ladar_driver) under the supervisor: Ctrl-C, crash loop, required process, kill -9;
//   - FleetNotify: a real node speaks systemd's notify protocol to a socket the test owns.

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <chrono>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <thread>

#include "common/node/bus.h"
#include "common/node/lcm_bus.h"
#include "minenav/heartbeat_t.hpp"
#include "tests/bus/private_bus_test.h"
#include "tests/child_process.h"
#include "tests/temp_dir.h"

namespace minenav {
namespace {

namespace fs = std::filesystem;
using SteadyClock = std::chrono::steady_clock;
using testing::ChildProcess;
using testing::LinesContaining;
using testing::ReadTextFile;
using testing::RunProgram;
using testing::TempDir;

const std::string kFleet = MINENAV_FLEET_BIN;
const std::string kBin = MINENAV_BIN_DIR;
const std::string kSource = MINENAV_SOURCE_DIR;

double SecondsSince(SteadyClock::time_point t0) {
  return std::chrono::duration<double>(SteadyClock::now() - t0).count();
}

// Polls `done` every 20 ms for at most `seconds`.
bool WaitFor(double seconds, const std::function<bool()>& done) {
  const auto t0 = SteadyClock::now();
  while (SecondsSince(t0) < seconds) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return done();
}

std::string WriteFile(const TempDir& dir, const std::string& name, const std::string& text) {
  const std::string path = dir / name;
  std::ofstream(path) << text;
  return path;
}

// The pids the supervisor reported starting NAME with, in order ("started NAME (pid N)").
std::vector<int> StartedPids(const std::string& output, const std::string& name) {
  std::vector<int> pids;
  const std::regex re("(?:re)?started " + name + " \\(pid ([0-9]+)");
  for (std::sregex_iterator it(output.begin(), output.end(), re), end; it != end; ++it)
    pids.push_back(std::stoi((*it)[1].str()));
  return pids;
}

// Gone, or a zombie waiting for whoever reaps orphans.
bool ProcessGone(int pid) {
  if (::kill(pid, 0) != 0 && errno == ESRCH) return true;
  const std::string stat = ReadTextFile("/proc/" + std::to_string(pid) + "/stat");
  const auto paren = stat.rfind(')');
  return paren != std::string::npos && paren + 2 < stat.size() && stat[paren + 2] == 'Z';
}

// ---------------------------------------------------------------------------------------
// No bus: reading fleet files.

TEST(FleetCli, CheckPrintsTheStartPlanInOrder) {
  TempDir dir("fleet_cli");
  const std::string file = WriteFile(dir, "a.fleet",
                                     "[process second]\ncommand = sleep ${T}\ngroup = base\nafter = first\n"
                                     "[process first]\ncommand = sleep 1\ngroup = vehicle\nheartbeat = none\n"
                                     "[variables]\nT = 5\n");
  const auto run = RunProgram(kFleet, {"check", file, "T=7"}, dir / "out.txt", 10);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto first = run.output.find("\nfirst ");
  const auto second = run.output.find("\nsecond ");
  ASSERT_NE(first, std::string::npos) << run.output;
  ASSERT_NE(second, std::string::npos) << run.output;
  EXPECT_LT(first, second) << "first comes first: second waits for it\n" << run.output;
  EXPECT_NE(run.output.find("/sleep 7"), std::string::npos) << "T=7 from the command line, sleep found on $PATH\n"
                                                           << run.output;
  EXPECT_NE(run.output.find("2 processes, groups: base vehicle"), std::string::npos) << run.output;
}

TEST(FleetCli, BadFleetFilesGetOneLineNamingFileLineAndKey) {
  TempDir dir("fleet_cli");
  const std::string bad_key = WriteFile(dir, "k.fleet", "[process a]\ncommand = sleep 1\ncolour = red\ngroup = g\n");
  const std::string no_program = WriteFile(dir, "p.fleet", "[process a]\n\ncommand = no_such_program_xyz 1\ngroup = g\n");
  struct Case {
    std::vector<std::string> args;
    std::string line;
  };
  const std::vector<Case> cases = {
      {{"check", bad_key}, "fleet check: error: " + bad_key + ":3: colour: unknown key"},
      {{"check", no_program}, "fleet check: error: " + no_program + ":3: command: no_such_program_xyz not found on $PATH"},
      // `fleet run` reads the file before it opens the bus: no namespace needed for this.
      {{"run", bad_key, "--out", dir / "o"}, "[fleet] error: " + bad_key + ":3: colour: unknown key"},
      {{"run", no_program, "X=1", "--out", dir / "o"}, "the file uses no variable X"},
      {{"check", dir / "missing.fleet"}, "missing.fleet: cannot open for reading"},
      {{"run", bad_key, "--groups", "g", "--restart.backoff-initial", "9", "--restart.backoff-max", "1"},
       "restart.backoff_max (1 s) is below restart.backoff_initial (9 s)"},
  };
  for (const Case& c : cases) {
    const auto run = RunProgram(kFleet, c.args, dir / "out.txt", 10);
    EXPECT_EQ(run.exit_code, 2) << c.args[0] << " " << c.args[1] << ": " << run.output;
    EXPECT_NE(run.output.find(c.line), std::string::npos) << run.output;
    EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << "one line:\n" << run.output;
  }
  EXPECT_FALSE(fs::exists(dir / "o")) << "nothing was started";
}

// The mission's fleet file (what scripts/run_demo.sh will start) stays valid, with the
// variables the demo passes.
TEST(FleetCli, TheMissionFleetFileChecksWithTheDemosVariables) {
  TempDir dir("fleet_cli");
  const auto run = RunProgram(kFleet,
                              {"check", kSource + "/fleet/mission.fleet", "--bin", kBin, "--out", dir / "demo",
                               "SEED=7", "TRAM_SPEED=1.0", "START_POSE=3,3,90deg", "FACE=5,3,0"},
                              dir / "out.txt", 10);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  for (const char* process : {"recorder", "vehicle_sim", "ladar_driver", "contour_mapper", "path_planner",
                              "path_tracker", "cutter", "task_planner", "coordinator"})
    EXPECT_EQ(LinesContaining(run.output, std::string(process) + " ").size() >= 1, true) << process << "\n" << run.output;
  EXPECT_NE(run.output.find("--vehicle.max-forward-speed 1.0"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("--start-pose 3,3,90deg"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("--face 5,3,0"), std::string::npos) << run.output;
}

TEST(FleetCli, UnitsWritesAServicePerProcessAndATargetPerGroup) {
  TempDir dir("fleet_cli");
  const auto run = RunProgram(kFleet,
                              {"units", kSource + "/fleet/mission.fleet", dir / "units", "--groups", "vehicle", "--bin",
                               "/opt/minenav/bin", "SEED=7", "TRAM_SPEED=1.0", "START_POSE=3,3,90deg", "FACE=5,3,0"},
                              dir / "out.txt", 10);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(fs::exists(dir / "units/minenav-vehicle.target"));
  EXPECT_FALSE(fs::exists(dir / "units/minenav-base.target"));
  const std::string sim = ReadTextFile(dir / "units/minenav-vehicle_sim.service");
  EXPECT_NE(sim.find("ExecStart=/opt/minenav/bin/vehicle_sim "), std::string::npos) << sim;
  EXPECT_NE(sim.find("Type=notify\n"), std::string::npos) << sim;
  EXPECT_NE(sim.find("WatchdogSec=10\n"), std::string::npos) << sim;
}

// ---------------------------------------------------------------------------------------
// systemd-analyze verify: reads the units as systemd would, without a running systemd.

std::string Verify(const std::vector<std::string>& units, const TempDir& dir) {
  const char* analyze = std::getenv("MINENAV_SYSTEMD_ANALYZE");
  if (analyze == nullptr) throw std::runtime_error("MINENAV_SYSTEMD_ANALYZE is not set (fleet/CMakeLists.txt sets it)");
  std::vector<std::string> args = {"verify"};
  args.insert(args.end(), units.begin(), units.end());
  const auto run = RunProgram(analyze, args, dir / "verify.txt", 60);
  return "exit " + std::to_string(run.exit_code) + "\n" + run.output;
}

TEST(FleetUnits, GeneratedUnitsPassSystemdAnalyzeVerify) {
  TempDir dir("fleet_units");
  const auto run = RunProgram(kFleet,
                              {"units", kSource + "/fleet/mission.fleet", dir / "units", "--bin", kBin, "--out",
                               dir / "var", "SEED=7", "TRAM_SPEED=1.0", "START_POSE=3,3,90deg", "FACE=5,3,0"},
                              dir / "out.txt", 10);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  std::vector<std::string> units;
  for (const auto& e : fs::directory_iterator(dir / "units")) units.push_back(e.path().string());
  ASSERT_GE(units.size(), 8u);
  EXPECT_EQ(Verify(units, dir), "exit 0\n");
  // The check is real: a unit with a mistake in it fails.
  std::ofstream(dir / "units/minenav-broken.service") << "[Service]\nType=notfy\nExecStart=" << kBin << "/vehicle_sim\n";
  EXPECT_NE(Verify({dir / "units/minenav-broken.service"}, dir), "exit 0\n");
}

TEST(FleetUnits, TheTemplateInDeployPassesSystemdAnalyzeVerify) {
  TempDir dir("fleet_units");
  // The template runs /opt/minenav/bin/%i: point it at this build for the check.
  std::string text = ReadTextFile(kSource + "/deploy/systemd/minenav@.service");
  ASSERT_NE(text.find("/opt/minenav/bin/%i"), std::string::npos);
  text = std::regex_replace(text, std::regex("/opt/minenav/bin"), kBin);
  std::ofstream(dir / "minenav@.service") << text;
  fs::copy_file(kSource + "/deploy/systemd/minenav.target", dir / "minenav.target");
  fs::create_symlink(dir / "minenav@.service", dir / "minenav@vehicle_sim.service");
  EXPECT_EQ(Verify({dir / "minenav@vehicle_sim.service", dir / "minenav.target"}, dir), "exit 0\n");
}

// ---------------------------------------------------------------------------------------
// The supervisor on a bus of its own.

class FleetRun : public testing::PrivateBusTest {
 protected:
  // Starts `fleet run FILE ARGS... --out DIR/out`, its stdout and stderr in DIR/fleet.txt.
  std::unique_ptr<ChildProcess> StartFleet(const std::string& file, const std::vector<std::string>& args) {
    std::vector<std::string> argv = {kFleet, "run", file, "--out", dir_ / "out", "--status-period", "0"};
    argv.insert(argv.end(), args.begin(), args.end());
    return std::make_unique<ChildProcess>(argv, output_path());
  }
  std::string output_path() const { return dir_ / "fleet.txt"; }
  std::string output() const { return ReadTextFile(output_path()); }
  bool OutputHas(const std::string& text) const { return output().find(text) != std::string::npos; }

  TempDir dir_{"fleet_run"};
};

TEST_F(FleetRun, CtrlCStopsEveryProcessWithinAFewSeconds) {
  const std::string file = WriteFile(dir_, "sleepers.fleet", R"(
[process a]
command = sleep 1000
group = g
heartbeat = none
[process b]
command = sleep 1000
group = g
heartbeat = none
after = a
# A shell that started another program: SIGINT ends the shell, and the program (which
# ignores SIGINT, as background jobs of a script do) goes with its process group.
[process c]
command = sh -c "sleep 1000 & echo $! > ${OUT}/c.pid; wait"
group = g
heartbeat = none
# It ignores SIGINT: the supervisor must SIGKILL it after the grace period.
[process stubborn]
command = sh -c 'trap "" INT; exec sleep 1000'
group = g
heartbeat = none
)");
  auto fleet = StartFleet(file, {"--stop-grace", "1"});
  ASSERT_TRUE(WaitFor(10, [&] { return StartedPids(output(), "(?:a|b|c|stubborn)").size() == 4; })) << output();
  std::vector<int> pids;
  for (const char* name : {"a", "b", "c", "stubborn"}) pids.push_back(StartedPids(output(), name).at(0));
  ASSERT_TRUE(WaitFor(5, [&] { return !ReadTextFile(dir_ / "out/c.pid").empty(); }));
  pids.push_back(std::stoi(ReadTextFile(dir_ / "out/c.pid")));  // c's sleep
  for (const int pid : pids) EXPECT_FALSE(ProcessGone(pid));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // let the shells install their traps

  const auto t0 = SteadyClock::now();
  fleet->Signal(SIGINT);
  const std::optional<int> code = fleet->Wait(10);
  const double took = SecondsSince(t0);
  ASSERT_TRUE(code.has_value()) << output();
  EXPECT_EQ(*code, 0) << output();
  EXPECT_LT(took, 2.5) << "SIGINT to each, SIGKILL after the 1 s grace:\n" << output();
  EXPECT_GE(took, 0.9) << "the stubborn one had its grace period\n" << output();
  for (const int pid : pids) EXPECT_TRUE(ProcessGone(pid)) << pid;
  EXPECT_TRUE(OutputHas("stubborn still running 1 s after SIGINT: SIGKILL")) << output();
  EXPECT_TRUE(OutputHas("stopped a (killed by SIGINT)")) << output();
  EXPECT_TRUE(OutputHas("stopped stubborn (killed by SIGKILL)")) << output();
}

// The supervisor's own descriptors (its LCM socket above all: liblcm opens it without
// close-on-exec) are not a child's: it has its standard input, output and error only.
TEST_F(FleetRun, AProcessHasItsStandardStreamsAndNoDescriptorOfTheSupervisor) {
  const std::string file = WriteFile(dir_, "sleeper.fleet", R"(
[process sleeper]
command = sleep 1000
group = g
heartbeat = none
)");
  auto fleet = StartFleet(file, {});
  ASSERT_TRUE(WaitFor(10, [&] { return StartedPids(output(), "sleeper").size() == 1; })) << output();
  const std::string fd_dir = "/proc/" + std::to_string(StartedPids(output(), "sleeper")[0]) + "/fd";
  // Until the exec has happened (the forked supervisor still has them all before it) and the
  // dynamic loader has closed the libraries it opens for a moment after it (CI once read
  // "3 -> .../libc.so.6" there).
  std::map<int, std::string> fds;  // descriptor -> what it is
  const auto list = [&] {
    fds.clear();
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(fd_dir, error)) {
      std::error_code link_error;
      fds[std::stoi(entry.path().filename().string())] = fs::read_symlink(entry.path(), link_error).string();
    }
    for (const auto& [fd, target] : fds)
      if (target.find(".so") != std::string::npos) return false;
    return true;
  };
  ASSERT_TRUE(WaitFor(5, [&] {
    return ReadTextFile(fd_dir.substr(0, fd_dir.size() - 3) + "/comm") == "sleep\n" && list();
  }));
  fleet->Signal(SIGINT);
  EXPECT_EQ(fleet->Wait(10), 0) << output();
  std::string listing;
  for (const auto& [fd, target] : fds) listing += std::to_string(fd) + " -> " + target + "\n";
  ASSERT_EQ(fds.size(), 3u) << listing;
  EXPECT_EQ(fds[0], "/dev/null") << listing;
  EXPECT_EQ(fds[2], dir_ / "out/sleeper.log") << listing;
  EXPECT_EQ(fds.count(1), 1u) << listing;
}

TEST_F(FleetRun, AScriptThatExitsAtOnceIsGivenUpAsACrashLoop) {
  const std::string file = WriteFile(dir_, "crash.fleet", R"(
[process crash]
command = sh -c 'echo boom >&2; exit 1'
group = g
heartbeat = none
[process steady]
command = sleep 1000
group = g
heartbeat = none
)");
  LcmBus bus(url_, 1000);
  std::vector<heartbeat_t> supervisor_heartbeats;
  Subscribe<heartbeat_t>(bus, "HEARTBEAT", [&](const heartbeat_t& m) {
    if (m.process == "fleet") supervisor_heartbeats.push_back(m);
  });
  const auto t0 = SteadyClock::now();
  auto fleet = StartFleet(file, {"--restart.backoff-initial", "0.1", "--restart.crash-loop-failures", "4",
                                 "--restart.crash-loop-window", "30", "--heartbeat-period", "0.2"});
  const std::string given_up = "crash GIVEN UP: crash loop: 4 failures within 30 s (last: exit code 1); no more restarts";
  ASSERT_TRUE(WaitFor(10, [&] { return OutputHas(given_up); })) << output();
  // Backoff 0.1, 0.2, 0.4 s between the 4 runs: at least 0.7 s.
  EXPECT_GE(SecondsSince(t0), 0.7) << output();
  EXPECT_EQ(StartedPids(output(), "crash").size(), 4u) << output();
  EXPECT_TRUE(OutputHas("crash exit code 1: restarting in 0.1 s (failure 1 in a row)")) << output();
  EXPECT_TRUE(OutputHas("crash exit code 1: restarting in 0.4 s (failure 3 in a row)")) << output();
  const std::string log = ReadTextFile(dir_ / "out/crash.log");
  size_t booms = 0;
  for (size_t at = log.find("\nboom\n"); at != std::string::npos; at = log.find("\nboom\n", at + 1)) ++booms;
  EXPECT_EQ(booms, 4u) << "each run's stderr in its log\n" << log;
  EXPECT_EQ(LinesContaining(log, "== fleet: ").size(), 4u) << log;
  // Nothing more is tried, and the rest goes on; the supervisor's heartbeat says what is wrong.
  std::this_thread::sleep_for(std::chrono::milliseconds(800));
  EXPECT_EQ(StartedPids(output(), "crash").size(), 4u);
  EXPECT_TRUE(fleet->Running());
  // (What was queued while the test waited comes first: pump until a heartbeat says it.)
  Pump(bus, 2.0, [&] {
    return !supervisor_heartbeats.empty() && supervisor_heartbeats.back().message.find("given up") != std::string::npos;
  });
  ASSERT_FALSE(supervisor_heartbeats.empty());
  EXPECT_EQ(supervisor_heartbeats.back().state, heartbeat_t::WARN);
  EXPECT_EQ(supervisor_heartbeats.back().message, "1 running, 1 given up; crash given up");
  // The table on demand (SIGUSR1).
  fleet->Signal(SIGUSR1);
  ASSERT_TRUE(WaitFor(5, [&] { return OutputHas("== fleet status at"); })) << output();
  EXPECT_EQ(LinesContaining(output(), "GIVEN UP: crash loop: 4 failures within 30 s (last: exit code 1)").size() >= 1, true)
      << output();
  fleet->Signal(SIGINT);
  EXPECT_EQ(fleet->Wait(5), 0) << output();
}

TEST_F(FleetRun, ARequiredProcessGivenUpStopsTheWholeFleet) {
  const std::string file = WriteFile(dir_, "required.fleet", R"(
[process essential]
command = sh -c 'exit 3'
group = g
heartbeat = none
required = true
[process other]
command = sleep 1000
group = g
heartbeat = none
)");
  auto fleet = StartFleet(file, {"--restart.backoff-initial", "0.05", "--restart.crash-loop-failures", "3"});
  const std::optional<int> code = fleet->Wait(10);
  ASSERT_TRUE(code.has_value()) << "the fleet stops by itself\n" << output();
  EXPECT_EQ(*code, 3) << output();
  EXPECT_TRUE(OutputHas("fleet ended: required process essential given up: crash loop: 3 failures within 60 s (last: exit "
                        "code 3)"))
      << output();
  const std::vector<int> other = StartedPids(output(), "other");
  ASSERT_EQ(other.size(), 1u) << output();
  EXPECT_TRUE(ProcessGone(other[0]));
  EXPECT_TRUE(OutputHas("stopped other")) << output();
}

TEST_F(FleetRun, AFleetProcessKilledWithSigkillIsRestartedAndItsHeartbeatComesBack) {
  const std::string file = WriteFile(dir_, "small.fleet", R"(
[process vehicle_sim]
command = ${BIN}/vehicle_sim --generate mine --seed 7 --start-pose auto --heartbeat-period 0.2
group = vehicle
ready = heartbeat
[process ladar_driver]
command = ${BIN}/ladar_driver --sensor typhoon --heartbeat-period 0.2
group = vehicle
after = vehicle_sim
)");
  LcmBus bus(url_, 1000);
  std::map<std::string, std::vector<heartbeat_t>> heartbeats;
  Subscribe<heartbeat_t>(bus, "HEARTBEAT", [&](const heartbeat_t& m) { heartbeats[m.process].push_back(m); });
  auto fleet = StartFleet(file, {});
  auto heard_from = [&](const std::string& process, int pid) {
    for (const heartbeat_t& h : heartbeats[process])
      if (h.pid == pid && h.state != heartbeat_t::STOPPING) return true;
    return false;
  };
  ASSERT_TRUE(Pump(bus, 20, [&] {
    const std::vector<int> sim = StartedPids(output(), "vehicle_sim");
    const std::vector<int> ladar = StartedPids(output(), "ladar_driver");
    return sim.size() == 1 && ladar.size() == 1 && heard_from("vehicle_sim", sim[0]) && heard_from("ladar_driver", ladar[0]);
  })) << output();
  const int first_pid = StartedPids(output(), "vehicle_sim")[0];
  EXPECT_LT(output().find("vehicle_sim ready"), output().find("started ladar_driver")) << "ladar_driver waits\n" << output();

  ASSERT_EQ(::kill(first_pid, SIGKILL), 0);
  const auto killed_at = SteadyClock::now();
  ASSERT_TRUE(Pump(bus, 15, [&] {
    const std::vector<int> sim = StartedPids(output(), "vehicle_sim");
    return sim.size() == 2 && heard_from("vehicle_sim", sim[1]);
  })) << output();
  EXPECT_TRUE(OutputHas("vehicle_sim killed by SIGKILL: restarting in 0.5 s (failure 1 in a row)")) << output();
  EXPECT_GE(SecondsSince(killed_at), 0.5) << "the backoff was waited";
  const int second_pid = StartedPids(output(), "vehicle_sim")[1];
  EXPECT_NE(second_pid, first_pid);
  // The ladar driver was never restarted and goes on with the new vehicle_sim: it handles
  // SIM_TRUTH again (its messages_in grows).
  EXPECT_EQ(StartedPids(output(), "ladar_driver").size(), 1u);
  const int64_t ladar_in = heartbeats["ladar_driver"].back().messages_in;
  Pump(bus, 1.0);
  EXPECT_GT(heartbeats["ladar_driver"].back().messages_in, ladar_in + 5);

  // `fleet status` on the bus sees the fleet, the new pid and message rates.
  const auto status = RunProgram(kFleet, {"status", "--for", "1.5"}, dir_ / "status.txt", 10);
  ASSERT_EQ(status.exit_code, 0) << status.output;
  const std::vector<std::string> sim_rows = LinesContaining(status.output, "vehicle_sim  ");
  ASSERT_EQ(sim_rows.size(), 1u) << status.output;
  EXPECT_NE(sim_rows[0].find(std::to_string(second_pid)), std::string::npos) << status.output;
  EXPECT_EQ(LinesContaining(status.output, "fleet:all  ").size(), 1u) << "the supervisor, its groups as instance\n"
                                                                   << status.output;
  const std::vector<std::string> ladar_rows = LinesContaining(status.output, "ladar_driver  ");
  ASSERT_EQ(ladar_rows.size(), 1u) << status.output;
  EXPECT_TRUE(std::regex_search(ladar_rows[0], std::regex("  OK +[0-9]+\\.[0-9]  "))) << "a rate\n" << status.output;

  // The supervisor's own table: vehicle_sim running, restarted once, its heartbeat fresh.
  fleet->Signal(SIGUSR1);
  ASSERT_TRUE(WaitFor(5, [&] { return OutputHas("== fleet status at"); })) << output();
  const std::regex row("vehicle_sim +vehicle +running +" + std::to_string(second_pid) + " +1 +0\\.[0-9] s +OK");
  EXPECT_TRUE(std::regex_search(output(), row)) << "running, restarted once, a fresh heartbeat\n" << output();

  fleet->Signal(SIGINT);
  const auto t0 = SteadyClock::now();
  EXPECT_EQ(fleet->Wait(10), 0) << output();
  EXPECT_LT(SecondsSince(t0), 2.0) << output();
  EXPECT_TRUE(ProcessGone(second_pid));
  Pump(bus, 0.3);
  EXPECT_EQ(heartbeats["vehicle_sim"].back().state, heartbeat_t::STOPPING) << "vehicle_sim stopped cleanly";
}

// ---------------------------------------------------------------------------------------
// A real node speaks systemd's notify protocol (common/node/node_runtime.h).

class FleetNotify : public testing::PrivateBusTest {};

TEST_F(FleetNotify, VehicleSimSendsReadyThenWatchdogsThenStopping) {
  TempDir dir("fleet_notify");
  const std::string socket_path = dir / "notify.sock";
  const int fd = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  socket_path.copy(address.sun_path, sizeof(address.sun_path) - 1);
  ASSERT_EQ(::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)), 0);
  timeval timeout{0, 100'000};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof(timeout));
  std::vector<std::pair<double, std::string>> got;  // (seconds since start, datagram)
  const auto t0 = SteadyClock::now();
  auto receive_for = [&](double seconds) {
    const auto until = SteadyClock::now() + std::chrono::duration<double>(seconds);
    char buffer[4096];
    while (SteadyClock::now() < until) {
      const ssize_t n = ::recv(fd, buffer, sizeof(buffer), 0);
      if (n > 0) got.emplace_back(SecondsSince(t0), std::string(buffer, static_cast<size_t>(n)));
    }
  };

  ::setenv("NOTIFY_SOCKET", socket_path.c_str(), 1);
  ::setenv("WATCHDOG_USEC", "400000", 1);  // WatchdogSec=0.4: a ping every 0.2 s
  ChildProcess sim({kBin + "/vehicle_sim", "--generate", "mine", "--seed", "7", "--start-pose", "auto"}, dir / "sim.txt");
  ::unsetenv("NOTIFY_SOCKET");
  ::unsetenv("WATCHDOG_USEC");
  receive_for(3.0);
  sim.Signal(SIGINT);
  EXPECT_EQ(sim.Wait(5), 0) << ReadTextFile(dir / "sim.txt");
  receive_for(0.3);
  ::close(fd);

  ASSERT_FALSE(got.empty()) << ReadTextFile(dir / "sim.txt");
  EXPECT_EQ(got.front().second, "READY=1\nSTATUS=running");
  std::vector<double> pings;
  for (const auto& [t, m] : got)
    if (m == "WATCHDOG=1") pings.push_back(t);
  ASSERT_GE(pings.size(), 2u);
  // About 3 s of pings at 0.2 s after READY (started at ~0.1-0.5 s).
  EXPECT_GE(pings.size(), 10u);
  EXPECT_LE(pings.size(), 16u);
  for (size_t k = 1; k < pings.size(); ++k) EXPECT_LT(pings[k] - pings[k - 1], 0.35) << k;
  EXPECT_EQ(std::count_if(got.begin(), got.end(), [](const auto& e) { return e.second == "STOPPING=1"; }), 1);
  const auto stopping = std::find_if(got.begin(), got.end(), [](const auto& e) { return e.second == "STOPPING=1"; });
  EXPECT_TRUE(std::none_of(stopping, got.end(), [](const auto& e) { return e.second == "WATCHDOG=1"; }))
      << "no ping after STOPPING";
  EXPECT_NE(std::find_if(got.begin(), got.end(), [](const auto& e) { return e.second.rfind("STATUS=OK", 0) == 0; }),
            got.end());
}

}  // namespace
}  // namespace minenav
