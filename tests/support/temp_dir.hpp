// A fresh, empty folder under the system's temporary directory for a test's files.
#pragma once

#include <filesystem>
#include <string>

namespace seismpm::test {

// <tmp>/seismpm_test_<name>, emptied and created.
inline std::string fresh_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("seismpm_test_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

}  // namespace seismpm::test
