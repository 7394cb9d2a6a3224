// SPDX-License-Identifier: MIT
#include "sewerplan/core/diagnostics.h"

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

std::string Diagnostics::error_summary() const {
  std::ostringstream out;
  bool first = true;
  for (const Diagnostic& d : kept_) {
    if (d.severity != Severity::kError) continue;
    if (!first) out << '\n';
    out << d;
    first = false;
  }
  if (dropped() > 0) out << "\n(" << dropped() << " more problems not shown)";
  return out.str();
}

}  // namespace sewerplan
