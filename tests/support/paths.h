// SPDX-License-Identifier: MIT
// Paths to the repository's data for tests: datasets/ and tests/data/.
#pragma once

#include <filesystem>
#include <string>

namespace sewerplan::testing {

inline std::filesystem::path source_dir() { return SEWERPLAN_SOURCE_DIR; }
inline std::filesystem::path dataset_path(const std::string& relative) {
  return source_dir() / "datasets" / relative;
}
inline std::filesystem::path test_data_path(const std::string& relative) {
  return source_dir() / "tests" / "data" / relative;
}

}  // namespace sewerplan::testing
