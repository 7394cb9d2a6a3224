// SPDX-License-Identifier: MIT
// Diagnostics: the problems found while reading or validating input, each naming where it is.
//
// Loaders and validators append to a Diagnostics list instead of stopping at the first problem,
// so that a user fixes a file in one pass. `where` is a file and line ("ais.sewer:12") or a file
// and JSON path ("map.json:$.pipes[3].length_m"); the message names the object ("pipe P5: ...").
// Errors make the load fail; warnings are reported and the load goes on with a documented
// fallback. A reader fails when its Diagnostics holds any error, including one added before it
// was called (readers such as MapBuilder::build rely on that to fail on their own earlier
// checks), so use one Diagnostics per file read and merge the lists for display if needed.
//
//   Diagnostics diagnostics;
//   auto map = read_map(path, diagnostics);
//   for (const Diagnostic& d : diagnostics.all()) std::cerr << d << '\n';
//
// Thread safety: A Diagnostics is not thread-safe: one per reader, on one thread at a time.
#pragma once

#include <cstddef>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace sewerplan {

enum class Severity { kWarning, kError };

struct Diagnostic {
  Severity severity;
  std::string where;
  std::string message;
  friend bool operator==(const Diagnostic&, const Diagnostic&) = default;
};

// "where: error: message"
std::ostream& operator<<(std::ostream& os, const Diagnostic& diagnostic);

class Diagnostics {
 public:
  // At most this many diagnostics are kept; later ones are only counted (a broken generated file
  // could otherwise produce millions of lines).
  static constexpr std::size_t kMaxKept = 200;

  void error(std::string where, std::string message);
  void warning(std::string where, std::string message);

  // Where this collection stands. A reader takes a mark when it starts, so that problems a caller
  // collected before (one Diagnostics reused across several files) neither fail the read nor
  // appear in its error.
  struct Mark {
    std::size_t errors = 0;
    std::size_t warnings = 0;
    std::size_t kept = 0;
  };
  Mark mark() const { return {errors_, warnings_, kept_.size()}; }
  bool has_errors_since(Mark since) const { return errors_ > since.errors; }

  const std::vector<Diagnostic>& all() const { return kept_; }
  std::size_t error_count() const { return errors_; }
  std::size_t warning_count() const { return warnings_; }
  bool has_errors() const { return errors_ > 0; }
  // Diagnostics dropped after kMaxKept.
  std::size_t dropped() const { return errors_ + warnings_ - kept_.size(); }

  // The kept errors since `since`, one "where: error: message" line each, plus a count of the
  // problems dropped since then; without a mark, all of them.
  std::string error_summary(Mark since) const;
  std::string error_summary() const { return error_summary(Mark{}); }

 private:
  void add(Severity severity, std::string where, std::string message);
  std::vector<Diagnostic> kept_;
  std::size_t errors_ = 0;
  std::size_t warnings_ = 0;
};

// Reports a JSON syntax error at "file:line:column", worked out from the byte offset (1-based,
// as nlohmann's parse_error::byte) into `text`; `what` is the parser's message, of which the part
// after "parse error ...: " is kept. Shared by every JSON reader so that all point the same way.
void report_json_syntax_error(std::string_view text, std::string_view file, std::size_t byte,
                              std::string_view what, Diagnostics& diagnostics);

}  // namespace sewerplan
