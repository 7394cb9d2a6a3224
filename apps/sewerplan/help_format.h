// SPDX-License-Identifier: MIT
// How every --help of the sewerplan command is laid out: CLI11's layout (usage line, options in
// two columns, subcommands, footer) with what a reader should not see taken out, and every line
// fitted to the terminal's width.
//
// What CLI11 2.1 prints and this does not: a hidden positional (the deprecated MAP of validate,
// info, convert and motion precompute) in the usage line as `[]` or `[(0x)]`; a range's type twice
// (`FLOAT:FLOAT in [0 - 86400]`: `FLOAT in [0 - 86400]`); descriptions as one line however long
// (here wrapped at word boundaries to the width, beside their option or indented under it).
//
// The width: $COLUMNS when it is a number from 40 to 500 (man_page.sh asks for 73, so that the
// man page's indented sections fit 80 columns), else 80. tests/cli/help_test.sh checks every
// command's --help for the artefacts and for lines over the width.
#pragma once

#include <cstddef>
#include <string>

#include <CLI/CLI.hpp>

namespace sewerplan::cli {

class HelpFormatter final : public CLI::Formatter {
 public:
  explicit HelpFormatter(std::size_t width);

  std::string make_usage(const CLI::App* app, std::string name) const override;
  std::string make_description(const CLI::App* app) const override;
  std::string make_option(const CLI::Option* opt, bool is_positional) const override;
  std::string make_option_opts(const CLI::Option* opt) const override;
  std::string make_subcommand(const CLI::App* sub) const override;
  std::string make_footer(const CLI::App* app) const override;

 private:
  // "  NAME" padded to the column, then `text` wrapped to the width (on a line of its own, under
  // the column, when NAME reaches it).
  std::string two_columns(const std::string& name, const std::string& text) const;

  std::size_t width_;
};

// The width for --help: $COLUMNS from 40 to 500, else 80.
std::size_t help_width();

}  // namespace sewerplan::cli
