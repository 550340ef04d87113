// log_tool import-carmen and log_tool relations on the real Intel log of the datasets folder
// (dataset_readers/dataset_path.h), as users run them; built only when the datasets are there
// (MINENAV_HAVE_DATASETS). The inline cases and bad input are in carmen_cli_test.cc.

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "dataset_readers/dataset_path.h"
#include "logger/log_tool_run.h"
#include "logger/test_logs.h"

namespace minenav {
namespace {

using logger_test::Dataset;
using logger_test::LogTool;
using logger_test::ReadAll;
using logger_test::RunResult;
using logger_test::TempPath;

// Intel end to end through the command line: import, info, and the GMapping known answer
// with the odometry read back from the imported log.
TEST(CarmenCli, IntelImportAndKnownAnswer) {
  const std::string lcm = TempPath("intel.lcm");
  const RunResult imp = LogTool("import-carmen " + Dataset("intel.clf.bz2") + " " + lcm);
  ASSERT_EQ(imp.exit_code, 0) << imp.err;
  const RunResult info = LogTool("info --json " + lcm);
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const nlohmann::json j = nlohmann::json::parse(info.out);
  std::map<std::string, int64_t> counts;
  for (const auto& c : j["channels"]) counts[c["channel"].get<std::string>()] = c["count"].get<int64_t>();
  EXPECT_EQ(counts["LADAR_SCAN"], 13631);
  EXPECT_EQ(counts["ODOMETRY"], 26915);

  const std::string json = TempPath("ka.json");
  const RunResult r = LogTool("relations --relations " + Dataset("intel.relations.txt") + " --poses " +
                              Dataset("intel-corrected.log.gz") + " --poses-time-shift 976052857.337284 --odometry " +
                              lcm + " --json-out " + json);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json s = nlohmann::json::parse(ReadAll(json));
  EXPECT_EQ(s["n"], 2984);
  EXPECT_NEAR(s["translation_m"]["mean"].get<double>(), 0.075, 0.005);
  EXPECT_NEAR(s["translation_m"]["std"].get<double>(), 0.086, 0.005);
  std::filesystem::remove(lcm);
}

}  // namespace
}  // namespace minenav
