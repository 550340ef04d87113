#pragma once
// The subcommands of log_tool (log_tool_main.cc dispatches). Each takes the arguments
// after its name, returns the process exit code, and throws UsageError / InputError
// (exit 2) for bad flags and input; main prints those as one line.

#include <string>
#include <vector>

namespace minenav {

int RunInfoCommand(const std::vector<std::string>& args);
int RunExportCommand(const std::vector<std::string>& args);
int RunRenderCommand(const std::vector<std::string>& args);
int RunSurveyCommand(const std::vector<std::string>& args);
int RunGenerateCommand(const std::vector<std::string>& args);
int RunRecordCommand(const std::vector<std::string>& args);
int RunImportCarmenCommand(const std::vector<std::string>& args);  // import_carmen_command.cc
int RunRelationsCommand(const std::vector<std::string>& args);     // relations_command.cc
int RunMissionReportCommand(const std::vector<std::string>& args); // mission_report_command.cc
int RunSpyCommand(const std::vector<std::string>& args);           // spy_command.cc
int RunExportMcapCommand(const std::vector<std::string>& args);    // export_mcap_command.cc
int RunJoinCommand(const std::vector<std::string>& args);          // join_command.cc

// Removes every occurrence of --name VALUE / --name=VALUE from args and returns the values
// in order (for flags that may repeat, which ConfigSchema does not support).
std::vector<std::string> TakeRepeatedFlag(std::vector<std::string>* args, const std::string& name);

// Rewrites a bare boolean flag (--json) as --json=true unless the next argument is a
// boolean word, so `info --json LOG` does not read LOG as the flag's value.
std::vector<std::string> ExpandBareBoolFlags(const std::vector<std::string>& args,
                                             const std::vector<std::string>& bool_flags);

// Throws UsageError when `path` is empty, naming the flag.
void RequireOutputPath(const std::string& path, const std::string& flag);

}  // namespace minenav
