#pragma once
// The public datasets (CARMEN logs, relations) for the real-data tests. They are data, never
// in the repository: CMake finds them at MINENAV_DATASETS_DIR (default ../shared/datasets,
// see its SOURCES.md) and builds the *_real_test executables only when they are there
// (MINENAV_HAVE_DATASETS), so a file missing here is a real failure, not a skip.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#ifndef MINENAV_DATASETS_DIR
#error "the real-data tests need MINENAV_DATASETS_DIR (logger/CMakeLists.txt defines it)"
#endif

namespace minenav::logger_test {

inline std::string DatasetsDir() { return MINENAV_DATASETS_DIR; }

// The path of a dataset file; a missing file fails the test (it does not skip it).
inline std::string Dataset(const std::string& name) {
  const std::string path = DatasetsDir() + "/" + name;
  if (!std::filesystem::exists(path))
    ADD_FAILURE() << "dataset " << path << " is missing (set MINENAV_DATASETS_DIR; see shared/datasets/SOURCES.md)";
  return path;
}

}  // namespace minenav::logger_test
