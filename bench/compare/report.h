// SPDX-License-Identifier: MIT
// The comparison's results: a CSV file written row by row as the runs finish (appended and flushed
// per instance through core/output_file.h's LogFile, so an interrupted comparison keeps what it
// measured), and a Markdown table with a summary at the end (written whole, atomically). Every
// write is checked: a failure is an error naming the file (the tool's exit 3).
#pragma once

#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "sewerplan/core/output_file.h"
#include "sewerplan/core/result.h"

#include "planners.h"

namespace sewerplan::compare {

class Report {
 public:
  // Creates the CSV file and writes its header; kIo naming it if it cannot.
  static Result<Report> open(const std::filesystem::path& csv,
                             const std::filesystem::path& markdown, std::string settings);

  // outcomes.front() is sewerplan's, the reference of the ratios.
  void add(const Instance& instance, const std::vector<Outcome>& outcomes);
  void skipped(const std::string& label, const std::string& why);
  // Writes the Markdown table and closes the CSV file: the first failed write of either (a row
  // that could not be appended, named with the file), if any.
  Result<void> finish();

 private:
  struct Row {
    std::string instance;
    std::size_t manholes = 0;
    std::size_t tasks = 0;
    std::vector<Outcome> outcomes;
  };
  void write_markdown(std::ostream& md) const;
  Report(LogFile csv, std::filesystem::path markdown, std::string settings)
      : csv_(std::move(csv)), markdown_(std::move(markdown)), settings_(std::move(settings)) {}
  LogFile csv_;
  std::filesystem::path markdown_;
  std::string settings_;
  std::vector<Row> rows_;
  std::vector<std::string> skipped_;
};

}  // namespace sewerplan::compare
