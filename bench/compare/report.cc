// SPDX-License-Identifier: MIT
#include "report.h"

#include <algorithm>
#include <iomanip>
#include <map>
#include <sstream>

namespace sewerplan::compare {
namespace {

std::string number(double v, int precision = 3) {
  std::ostringstream s;
  s << std::setprecision(precision) << v;
  return s.str();
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// How many times slower than sewerplan (by whole-process wall time), when both solved.
std::optional<double> time_ratio(const Outcome& o, const Outcome& reference) {
  if (!o.solved() || !reference.solved() || reference.wall_s <= 0) return std::nullopt;
  return o.wall_s / reference.wall_s;
}

std::optional<double> cost_ratio(const Outcome& o, const Outcome& reference) {
  if (!o.solved() || !reference.solved() || !o.cost_s || !reference.cost_s ||
      *reference.cost_s <= 0) {
    return std::nullopt;
  }
  return *o.cost_s / *reference.cost_s;
}

std::string optional_number(const std::optional<double>& v, int precision = 4) {
  return v ? number(*v, precision) : "";
}

}  // namespace

Result<Report> Report::open(const std::filesystem::path& csv, const std::filesystem::path& markdown,
                            std::string settings) {
  Result<LogFile> file = LogFile::open(csv);
  if (!file.has_value()) return file.error();
  Report report(std::move(*file), markdown, std::move(settings));
  if (!report.csv_.append("instance,manholes,tasks,planner,status,wall_s,load_and_plan_s,cost_s,"
                          "steps,peak_mb,time_ratio,cost_ratio,detail\n")) {
    return Error{ErrorCode::kIo, *report.csv_.first_error()};
  }
  return report;
}

void Report::add(const Instance& instance, const std::vector<Outcome>& outcomes) {
  const Outcome& reference = outcomes.front();
  std::ostringstream csv;
  for (const Outcome& o : outcomes) {
    csv << csv_field(instance.name) << ',' << instance.manholes << ',' << instance.tasks << ','
        << csv_field(o.planner) << ',' << csv_field(o.status) << ',' << number(o.wall_s, 6) << ','
        << optional_number(o.load_and_plan_s, 6) << ',' << optional_number(o.cost_s, 7) << ','
        << (o.steps ? std::to_string(*o.steps) : "") << ',' << number(o.peak_mb, 5) << ','
        << optional_number(time_ratio(o, reference)) << ','
        << optional_number(cost_ratio(o, reference)) << ',' << csv_field(o.detail) << '\n';
  }
  csv_.append(csv.str());  // a failure is kept and reported by finish()
  rows_.push_back({instance.name, instance.manholes, instance.tasks, outcomes});
}

void Report::skipped(const std::string& label, const std::string& why) {
  skipped_.push_back(label + ": " + why);
}

Result<void> Report::finish() {
  std::ostringstream md;
  write_markdown(md);
  Result<void> table = write_text_file(markdown_, md.str());
  Result<void> rows = csv_.close();
  return !rows.has_value() ? rows : table;
}

void Report::write_markdown(std::ostream& md) const {
  md << "# sewerplan against external planners\n\n" << settings_ << ".\n\n";
  md << "Times are whole-process wall times (sewerplan's own load-and-plan time in brackets); "
        "costs are in seconds by sewerplan's cost model, for plans its validator accepts; "
        "`x` columns are the planner's time and cost over sewerplan's.\n\n";
  if (rows_.empty()) return;
  const std::size_t planners = rows_.front().outcomes.size();
  md << "| instance | manholes | tasks ";
  for (std::size_t p = 0; p < planners; ++p) {
    const std::string& name = rows_.front().outcomes[p].planner;
    md << "| " << name << " | s | cost s | MiB ";
    if (p > 0) md << "| x time | x cost ";
  }
  md << "|\n|---|--:|--:";
  for (std::size_t p = 0; p < planners; ++p)
    md << (p > 0 ? "|---|--:|--:|--:|--:|--:" : "|---|--:|--:|--:");
  md << "|\n";
  std::map<std::string, std::pair<std::size_t, std::size_t>> solved;  // planner -> solved, runs
  std::map<std::string, std::vector<double>> ratios;
  for (const Row& row : rows_) {
    md << "| " << row.instance << " | " << row.manholes << " | " << row.tasks << ' ';
    const Outcome& reference = row.outcomes.front();
    for (std::size_t p = 0; p < row.outcomes.size(); ++p) {
      const Outcome& o = row.outcomes[p];
      solved[o.planner].second++;
      if (o.solved()) solved[o.planner].first++;
      md << "| " << o.status << (o.detail.empty() || o.solved() ? "" : " (" + o.detail + ")")
         << " | " << number(o.wall_s, 3);
      if (o.load_and_plan_s) md << " (" << number(*o.load_and_plan_s, 3) << ")";
      md << " | " << optional_number(o.cost_s, 5) << " | " << number(o.peak_mb, 4) << ' ';
      if (p > 0) {
        const auto t = time_ratio(o, reference);
        if (t) ratios[o.planner].push_back(*t);
        md << "| " << optional_number(t, 3) << " | " << optional_number(cost_ratio(o, reference), 4)
           << ' ';
      }
    }
    md << "|\n";
  }
  md << "\n## Summary\n\n";
  for (const auto& [planner, counts] : solved) {
    md << "- " << planner << ": solved " << counts.first << " of " << counts.second;
    if (auto r = ratios.find(planner); r != ratios.end() && !r->second.empty()) {
      std::vector<double> v = r->second;
      std::sort(v.begin(), v.end());
      md << "; time over sewerplan's where both solved: min " << number(v.front()) << "x, median "
         << number(v[v.size() / 2]) << "x, max " << number(v.back()) << "x";
    }
    md << '\n';
  }
  for (const std::string& s : skipped_) md << "- skipped " << s << '\n';
}

}  // namespace sewerplan::compare
