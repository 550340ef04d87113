#pragma once
// The tests' side of common/child_process.h (the runner), and two text helpers.

#include <string>
#include <vector>

#include "common/child_process.h"

namespace minenav::testing {

using ::minenav::ChildProcess;
using ::minenav::ProgramRun;
using ::minenav::RunProgram;

// The whole file as a string ("" if it cannot be read).
std::string ReadTextFile(const std::string& path);
// Lines of `text` containing `needle`.
std::vector<std::string> LinesContaining(const std::string& text, const std::string& needle);

}  // namespace minenav::testing
