// SPDX-License-Identifier: MIT
// The comparison's results: a CSV file written row by row as the runs finish (so an interrupted
// comparison keeps what it measured), and a Markdown table with a summary at the end.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "planners.h"

namespace sewerplan::compare {

class Report {
 public:
  Report(const std::filesystem::path& csv, const std::filesystem::path& markdown,
         std::string settings);

  // outcomes.front() is sewerplan's, the reference of the ratios.
  void add(const Instance& instance, const std::vector<Outcome>& outcomes);
  void skipped(const std::string& label, const std::string& why);
  void finish();

 private:
  struct Row {
    std::string instance;
    std::size_t manholes = 0;
    std::size_t tasks = 0;
    std::vector<Outcome> outcomes;
  };
  std::ofstream csv_;
  std::filesystem::path markdown_;
  std::string settings_;
  std::vector<Row> rows_;
  std::vector<std::string> skipped_;
};

}  // namespace sewerplan::compare
