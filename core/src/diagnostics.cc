// SPDX-License-Identifier: MIT
#include "sewerplan/core/diagnostics.h"

#include <algorithm>
#include <sstream>

namespace sewerplan {

std::ostream& operator<<(std::ostream& os, const Diagnostic& diagnostic) {
  if (!diagnostic.where.empty()) os << diagnostic.where << ": ";
  os << (diagnostic.severity == Severity::kError ? "error: " : "warning: ") << diagnostic.message;
  return os;
}

void Diagnostics::error(std::string where, std::string message) {
  ++errors_;
  add(Severity::kError, std::move(where), std::move(message));
}

void Diagnostics::warning(std::string where, std::string message) {
  ++warnings_;
  add(Severity::kWarning, std::move(where), std::move(message));
}

void Diagnostics::add(Severity severity, std::string where, std::string message) {
  if (kept_.size() < kMaxKept) kept_.push_back({severity, std::move(where), std::move(message)});
}

std::string Diagnostics::error_summary(Mark since) const {
  std::ostringstream out;
  bool first = true;
  for (std::size_t i = std::min(since.kept, kept_.size()); i < kept_.size(); ++i) {
    const Diagnostic& d = kept_[i];
    if (d.severity != Severity::kError) continue;
    if (!first) out << '\n';
    out << d;
    first = false;
  }
  const std::size_t dropped_before = since.errors + since.warnings - since.kept;
  if (dropped() > dropped_before) {
    out << "\n(" << dropped() - dropped_before << " more problems not shown)";
  }
  return out.str();
}

void report_json_syntax_error(std::string_view text, std::string_view file, std::size_t byte,
                              std::string_view what, Diagnostics& diagnostics) {
  const std::size_t offset = std::min<std::size_t>(byte == 0 ? 0 : byte - 1, text.size());
  const std::string_view before = text.substr(0, offset);
  const auto line = 1 + static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
  const std::size_t line_start = before.rfind('\n');
  const std::size_t column =
      line_start == std::string_view::npos ? offset + 1 : offset - line_start;
  std::string message(what);
  // "[json.exception.parse_error.101] parse error at line 3, column 16: syntax error ..."
  if (auto colon = message.find(": ", message.find("parse error")); colon != std::string::npos) {
    message = message.substr(colon + 2);
  }
  diagnostics.error(std::string(file) + ":" + std::to_string(line) + ":" + std::to_string(column),
                    "JSON syntax error: " + message);
}

}  // namespace sewerplan
