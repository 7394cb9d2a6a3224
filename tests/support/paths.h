// SPDX-License-Identifier: MIT
// Paths to the repository's data for tests: datasets/ and tests/data/.
#pragma once

#include <filesystem>
#include <string>

namespace sewerplan::testing {

// The source tree's root. Only paths.cc knows it (a private definition), so the test files'
// compile lines name no machine path and a compiler cache shares them between checkouts.
std::filesystem::path source_dir();
inline std::filesystem::path dataset_path(const std::string& relative) {
  return source_dir() / "datasets" / relative;
}
inline std::filesystem::path test_data_path(const std::string& relative) {
  return source_dir() / "tests" / "data" / relative;
}

}  // namespace sewerplan::testing
