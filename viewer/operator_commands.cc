#include "viewer/operator_commands.h"

#include <utility>

#include <nlohmann/json.hpp>

namespace minenav {

// The largest payload a command needs ({"command":"RESUME"} is 20 bytes).
constexpr size_t kMaxCommandPayload = 1024;

std::optional<int8_t> OperatorCommandCode(std::string_view name) {
  if (name == "START") return coordinator_command_t::START;
  if (name == "PAUSE") return coordinator_command_t::PAUSE;
  if (name == "RESUME") return coordinator_command_t::RESUME;
  if (name == "ABORT") return coordinator_command_t::ABORT;
  if (name == "ESTOP") return coordinator_command_t::ESTOP;
  return std::nullopt;
}

OperatorCommands::OperatorCommands(bool allow, std::unique_ptr<CommandAuthority> authority)
    : allow_(allow), authority_(std::move(authority)) {}

OperatorCommandResult OperatorCommands::Refuse(std::string why) {
  ++refused_;
  return {std::nullopt, std::move(why)};
}

OperatorCommandResult OperatorCommands::Accept(std::string_view payload, int64_t now) {
  if (!allow_) return Refuse("operator commands are refused: the bridge was not started with --allow-commands");
  if (payload.size() > kMaxCommandPayload)
    return Refuse("command payload of " + std::to_string(payload.size()) + " bytes (at most 1024)");
  const nlohmann::json j = nlohmann::json::parse(payload, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return Refuse("command payload is not a JSON object");
  if (j.size() != 1 || !j.contains("command") || !j["command"].is_string())
    return Refuse("command payload must be exactly {\"command\": \"START|PAUSE|RESUME|ABORT|ESTOP\"}");
  const std::string name = j["command"].get<std::string>();
  const std::optional<int8_t> code = OperatorCommandCode(name);
  if (!code) return Refuse("unknown command \"" + name.substr(0, 20) + "\" (START, PAUSE, RESUME, ABORT or ESTOP)");
  coordinator_command_t m{};
  m.utime = now;
  m.seq = seq_ + 1;
  m.command = *code;
  m.argument = "";
  if (std::string why = authority_->Authorize(m); !why.empty()) return Refuse(std::move(why));
  ++seq_;
  return {m, ""};
}

}  // namespace minenav
