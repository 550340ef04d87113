#include "viewer/operator_commands.h"

#include <gtest/gtest.h>

namespace minenav {
namespace {

TEST(OperatorCommandsTest, RefusedWithoutTheFlag) {
  OperatorCommands c(false, std::make_unique<UnsignedCommandAuthority>());
  const OperatorCommandResult r = c.Accept(R"({"command":"ESTOP"})", 5);
  EXPECT_FALSE(r.command);
  EXPECT_NE(r.error.find("--allow-commands"), std::string::npos) << r.error;
  EXPECT_EQ(c.refused(), 1);
}

TEST(OperatorCommandsTest, EachOfTheFiveBecomesItsCoordinatorCommand) {
  OperatorCommands c(true, std::make_unique<UnsignedCommandAuthority>());
  const std::vector<std::pair<std::string, int8_t>> cases = {
      {"START", coordinator_command_t::START}, {"PAUSE", coordinator_command_t::PAUSE},
      {"RESUME", coordinator_command_t::RESUME}, {"ABORT", coordinator_command_t::ABORT},
      {"ESTOP", coordinator_command_t::ESTOP}};
  int64_t seq = 0;
  for (const auto& [name, code] : cases) {
    const OperatorCommandResult r = c.Accept(R"({"command":")" + name + "\"}", 1000 + seq);
    ASSERT_TRUE(r.command) << r.error;
    EXPECT_EQ(r.command->command, code);
    EXPECT_EQ(r.command->seq, ++seq);
    EXPECT_EQ(r.command->utime, 1000 + seq - 1);
    EXPECT_EQ(r.command->argument, "");
  }
}

TEST(OperatorCommandsTest, AnythingElseIsRefusedInOneLine) {
  OperatorCommands c(true, std::make_unique<UnsignedCommandAuthority>());
  for (const std::string& payload :
       {std::string("PAUSE"), std::string("{}"), std::string(R"({"command":"LOAD_MISSION"})"),
        std::string(R"({"command":"pause"})"), std::string(R"({"command":1})"),
        std::string(R"({"command":"PAUSE","argument":"/etc/passwd"})"), std::string(R"(["PAUSE"])"),
        R"({"command":")" + std::string(5000, 'A') + "\"}"}) {
    const OperatorCommandResult r = c.Accept(payload, 1);
    EXPECT_FALSE(r.command) << payload;
    EXPECT_FALSE(r.error.empty());
    EXPECT_EQ(r.error.find('\n'), std::string::npos);
    EXPECT_LT(r.error.size(), 200u);
  }
  EXPECT_EQ(c.accepted(), 0);
}

class RefusingAuthority final : public CommandAuthority {
 public:
  std::string Authorize(coordinator_command_t&) override { return "not signed"; }
};

TEST(OperatorCommandsTest, TheAuthorityHasTheLastWord) {
  OperatorCommands c(true, std::make_unique<RefusingAuthority>());
  const OperatorCommandResult r = c.Accept(R"({"command":"START"})", 1);
  EXPECT_FALSE(r.command);
  EXPECT_EQ(r.error, "not signed");
}

}  // namespace
}  // namespace minenav
