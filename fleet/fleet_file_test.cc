#include "fleet/fleet_file.h"

#include <gtest/gtest.h>

#include "common/file_io.h"

namespace minenav {
namespace {

const std::map<std::string, std::string> kBuiltins = {
    {"OUT", "/tmp/run 1"}, {"BIN", "/opt/minenav/bin"}, {"FLEET_DIR", "/src/fleet"}};

FleetSpec Parse(const std::string& text, const std::map<std::string, std::string>& overrides = {}) {
  return ParseFleetFile(text, "m.fleet", kBuiltins, overrides);
}

// The one-line error a text gets ("" when it parses).
std::string ErrorOf(const std::string& text, const std::map<std::string, std::string>& overrides = {}) {
  try {
    Parse(text, overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

constexpr const char* kMission = R"(# a fleet
[variables]
WORLD = ${OUT}/mine.json   # the generated world
SPEED = 1.0

[process world]
command = ${BIN}/log_tool generate --kind mine --world-out ${WORLD}
group = vehicle
restart = never

[process vehicle_sim]
command = ${BIN}/vehicle_sim --world ${WORLD} \
          --max-forward-speed ${SPEED} --title 'run #2 of "${SPEED}"' "${OUT}/a b" $$HOME
group = vehicle
after = world
ready = heartbeat
required = yes
env.LCM_DEFAULT_URL = udpm://239.255.76.67:7667?ttl=1

[process logger]
command = lcm-logger --quiet ${OUT}/survey.lcm
group = base
heartbeat = none
restart = always
stdout = log

[process tracker]
command = ${BIN}/path_tracker
group = vehicle
after = vehicle_sim, logger
ready = ok
heartbeat = path_tracker:left
ends_fleet = true
ready_timeout = 2.5
)";

TEST(FleetFile, ParsesProcessesVariablesQuotesAndContinuations) {
  const FleetSpec fleet = Parse(kMission);
  ASSERT_EQ(fleet.processes.size(), 4u);
  EXPECT_EQ(fleet.Groups(), (std::vector<std::string>{"vehicle", "base"}));

  const ProcessSpec& world = fleet.processes[0];
  EXPECT_EQ(world.argv, (std::vector<std::string>{"/opt/minenav/bin/log_tool", "generate", "--kind", "mine",
                                                  "--world-out", "/tmp/run 1/mine.json"}))
      << "a variable's value (with a blank) stays one word";
  EXPECT_EQ(world.restart, RestartPolicy::kNever);
  EXPECT_EQ(world.heartbeat_process, "log_tool") << "default: the program's name";
  EXPECT_EQ(world.Where(), "m.fleet:6");

  const ProcessSpec& sim = fleet.processes[1];
  EXPECT_EQ(sim.argv, (std::vector<std::string>{"/opt/minenav/bin/vehicle_sim", "--world", "/tmp/run 1/mine.json",
                                                "--max-forward-speed", "1.0", "--title", "run #2 of \"${SPEED}\"",
                                                "/tmp/run 1/a b", "$HOME"}))
      << "'...' is literal, \"...\" expands, $$ is $, a quoted # is no comment";
  EXPECT_EQ(sim.after, (std::vector<std::string>{"world"}));
  EXPECT_EQ(sim.ready, Readiness::kHeartbeat);
  EXPECT_TRUE(sim.required);
  EXPECT_FALSE(sim.ends_fleet);
  EXPECT_EQ(sim.env.at("LCM_DEFAULT_URL"), "udpm://239.255.76.67:7667?ttl=1");
  EXPECT_EQ(sim.Where("ready"), "m.fleet:16: ready");

  const ProcessSpec& logger = fleet.processes[2];
  EXPECT_FALSE(logger.has_heartbeat());
  EXPECT_EQ(logger.restart, RestartPolicy::kAlways);
  EXPECT_TRUE(logger.stdout_to_log);

  const ProcessSpec& tracker = fleet.processes[3];
  EXPECT_EQ(tracker.after, (std::vector<std::string>{"vehicle_sim", "logger"}));
  EXPECT_EQ(tracker.heartbeat_process, "path_tracker");
  EXPECT_EQ(tracker.heartbeat_instance, "left");
  EXPECT_EQ(tracker.ready, Readiness::kOk);
  EXPECT_DOUBLE_EQ(tracker.ready_timeout, 2.5);
  EXPECT_TRUE(tracker.ends_fleet);
  EXPECT_EQ(tracker.restart, RestartPolicy::kOnFailure) << "the default";

  EXPECT_EQ(fleet.variables.at("WORLD"), "/tmp/run 1/mine.json");
}

TEST(FleetFile, CommandLineValuesReplaceDefaultsAndDefineTheRest) {
  const FleetSpec fleet = Parse(kMission, {{"SPEED", "0.25"}});
  EXPECT_EQ(fleet.processes[1].argv[4], "0.25");
  const std::string text = "[process a]\ncommand = run ${START}\ngroup = g\n";
  EXPECT_EQ(Parse(text, {{"START", "1,2,0"}}).processes[0].argv, (std::vector<std::string>{"run", "1,2,0"}));
}

TEST(FleetFile, ErrorsNameFileLineAndKey) {
  EXPECT_EQ(ErrorOf("[process a]\ncommand = x\ngroup = g\nrestart = sometimes\n"),
            "m.fleet:4: restart: 'sometimes' is not one of never, on-failure, always");
  EXPECT_EQ(ErrorOf("[process a]\ncommand = x\ngroup = g\ncolour = red\n"),
            "m.fleet:4: colour: unknown key (a process has command, group, restart, after, ready, ready_timeout, "
            "heartbeat, required, ends_fleet, stdout, env.NAME)");
  EXPECT_EQ(ErrorOf("[process a]\ncommand = x ${NOPE}\ngroup = g\n"),
            "m.fleet:2: command: ${NOPE} is not defined (define it under [variables] or give NOPE=VALUE on the "
            "command line)");
  EXPECT_EQ(ErrorOf("[process a]\ncommand = x\ngroup = g\ncommand = y\n"), "m.fleet:4: command: given twice (first on line 2)");
  EXPECT_EQ(ErrorOf("[process a]\ngroup = g\n"), "m.fleet:1: [process a] has no command");
  EXPECT_EQ(ErrorOf("[process a]\ncommand = x\n"), "m.fleet:1: [process a] has no group (vehicle, base, ...)");
  EXPECT_EQ(ErrorOf("[process a]\ncommand = x 'open\ngroup = g\n"), "m.fleet:2: command: a ' quote is not closed");
  EXPECT_EQ(ErrorOf("[process a]\ncommand = x\ngroup = g\nafter = b\n"), "m.fleet:4: after: no process is called 'b'");
  EXPECT_EQ(ErrorOf("[process a]\ncommand = x\ngroup = g\nready = heartbeat\nheartbeat = none\n"),
            "m.fleet:4: ready: 'heartbeat' needs a heartbeat, but heartbeat = none");
  EXPECT_EQ(ErrorOf("[process a]\ncommand = x\ngroup = g\nready_timeout = -1\n"),
            "m.fleet:4: ready_timeout: -1 is outside (0, 3600] s");
  EXPECT_EQ(ErrorOf("[process a]\ncommand = x\ngroup = g\nrequired = maybe\n"),
            "m.fleet:4: required: 'maybe' is not true or false");
  EXPECT_EQ(ErrorOf("[proc a]\n"), "m.fleet:1: unknown section '[proc a]' (expected [variables] or [process NAME])");
  EXPECT_EQ(ErrorOf("[process a/b]\n"),
            "m.fleet:1: '[process a/b]': a process name is letters, digits, '_' and '-' ([process vehicle_sim])");
  EXPECT_EQ(ErrorOf("command = x\n"), "m.fleet:1: command: outside any section (start with [variables] or [process NAME])");
  EXPECT_EQ(ErrorOf("[variables]\nOUT = /x\n[process a]\ncommand = x\ngroup = g\n"),
            "m.fleet:2: OUT: OUT is built in and cannot be redefined");
  EXPECT_EQ(ErrorOf("[process a]\ncommand = x\ngroup = g\n", {{"SPEDE", "1"}}),
            "m.fleet: SPEDE=1 on the command line: the file uses no variable SPEDE");
  EXPECT_EQ(ErrorOf("[process a]\ncommand = x\ngroup = g\n", {{"OUT", "/y"}}),
            "m.fleet: OUT is built in: set the output folder with --out");
  EXPECT_EQ(ErrorOf("# nothing\n"), "m.fleet: no [process NAME] section");
  EXPECT_EQ(ErrorOf("[process a]\ncommand = x \\\n"), "m.fleet:2: the file ends after a '\\'");
}

TEST(FleetFile, CyclesAreRefusedWithTheChain) {
  const std::string text =
      "[process a]\ncommand = x\ngroup = g\nafter = c\n"
      "[process b]\ncommand = x\ngroup = g\nafter = a\n"
      "[process c]\ncommand = x\ngroup = g\nafter = b\n";
  EXPECT_EQ(ErrorOf(text), "m.fleet:4: after: the processes wait for each other: a -> c -> b -> a");
  EXPECT_EQ(ErrorOf("[process a]\ncommand = x\ngroup = g\nafter = a\n"), "m.fleet:4: after: a process cannot wait for itself");
}

TEST(FleetFile, StartOrderPutsEachAfterWhatItWaitsFor) {
  const std::string text =
      "[process c]\ncommand = x\ngroup = g\nafter = b\n"
      "[process a]\ncommand = x\ngroup = g\n"
      "[process b]\ncommand = x\ngroup = g\nafter = a\n"
      "[process d]\ncommand = x\ngroup = g\n";
  const FleetSpec fleet = Parse(text);
  std::vector<std::string> names;
  for (const size_t i : StartOrder(fleet)) names.push_back(fleet.processes[i].name);
  EXPECT_EQ(names, (std::vector<std::string>{"a", "d", "b", "c"}));
}

TEST(FleetFile, SelectingAGroupDropsWaitsForTheOtherHost) {
  const FleetSpec fleet = Parse(kMission);
  const FleetSpec vehicle = SelectGroups(fleet, {"vehicle"});
  ASSERT_EQ(vehicle.processes.size(), 3u);
  EXPECT_EQ(vehicle.processes[2].name, "tracker");
  EXPECT_EQ(vehicle.processes[2].after, (std::vector<std::string>{"vehicle_sim"})) << "logger runs on the base";
  EXPECT_EQ(SelectGroups(fleet, {}).processes.size(), 4u);
  try {
    SelectGroups(fleet, {"boat"});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "m.fleet: no process is in group 'boat' (its groups: vehicle, base)");
  }
}

TEST(FleetFile, OverridesAndQuoting) {
  EXPECT_EQ(ParseOverrides({"A=1", "B_2=x=y", "C="}),
            (std::map<std::string, std::string>{{"A", "1"}, {"B_2", "x=y"}, {"C", ""}}));
  EXPECT_THROW(ParseOverrides({"nothing"}), InputError);
  EXPECT_THROW(ParseOverrides({"1A=2"}), InputError);
  EXPECT_EQ(QuoteCommand({"/bin/x", "--a=1,2", "two words", "it's"}), "/bin/x --a=1,2 'two words' 'it'\\''s'");
}

}  // namespace
}  // namespace minenav
