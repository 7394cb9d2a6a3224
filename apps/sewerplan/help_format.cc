// SPDX-License-Identifier: MIT
#include "help_format.h"

#include <charconv>
#include <cstdlib>
#include <string_view>

namespace sewerplan::cli {
namespace {

// `text` wrapped at spaces into lines of at most `width` characters (a word longer than a line
// broken after a ';' or ',', else standing alone); a newline in `text` always breaks. Lines after
// the first start with `indent` spaces, the first with none (the caller has placed it).
std::string wrapped(std::string_view text, std::size_t indent, std::size_t first_width,
                    std::size_t width) {
  std::string out;
  std::size_t line_length = 0;
  std::size_t room = first_width;
  auto new_line = [&] {
    out += '\n';
    out.append(indent, ' ');
    line_length = 0;
    room = width > indent ? width - indent : 1;
  };
  std::size_t i = 0;
  while (i < text.size()) {
    if (text[i] == '\n') {
      new_line();
      ++i;
      continue;
    }
    if (text[i] == ' ') {
      ++i;
      continue;
    }
    std::size_t end = i;
    while (end < text.size() && text[end] != ' ' && text[end] != '\n') ++end;
    const std::string_view word = text.substr(i, end - i);
    if (line_length > 0 && line_length + 1 + word.size() > room) new_line();
    if (line_length == 0 && word.size() > room) {
      // Too long for any line: broken after its last ';' or ',' that fits ("a=1;b=2;...").
      const std::size_t cut = word.substr(0, room).find_last_of(";,");
      if (cut != std::string_view::npos) {
        out += word.substr(0, cut + 1);
        new_line();
        i += cut + 1;
        continue;
      }
    }
    if (line_length > 0) {
      out += ' ';
      ++line_length;
    }
    out += word;
    line_length += word.size();
    i = end;
  }
  return out;
}

}  // namespace

HelpFormatter::HelpFormatter(std::size_t width) : width_(width) {}

std::string HelpFormatter::two_columns(const std::string& name, const std::string& text) const {
  const std::size_t column = get_column_width();
  std::string out = "  " + name;
  if (text.empty()) return out + '\n';
  if (out.size() + 1 > column) {
    out += '\n';
    out.append(column, ' ');
  } else {
    out.append(column - out.size(), ' ');
  }
  return out + wrapped(text, column, width_ - column, width_) + '\n';
}

std::string HelpFormatter::make_usage(const CLI::App* app, std::string name) const {
  std::string usage = get_label("Usage") + ":";
  if (!name.empty()) usage += " " + name;
  if (!app->get_options([](const CLI::Option* o) { return o->nonpositional(); }).empty()) {
    usage += " [" + get_label("OPTIONS") + "]";
  }
  // The positionals a reader is shown (a hidden one, in no group, is deprecated and not shown).
  for (const CLI::Option* o : app->get_options([](const CLI::Option* option) {
         return option->get_positional() && !option->get_group().empty();
       })) {
    usage += " " + make_option_usage(o);
  }
  if (!app->get_subcommands(
              [](const CLI::App* sub) { return !sub->get_disabled() && !sub->get_name().empty(); })
           .empty()) {
    const std::string label = get_label("SUBCOMMAND");
    usage += app->get_require_subcommand_min() == 0 ? " [" + label + "]" : " " + label;
  }
  return wrapped(usage, 4, width_, width_) + '\n';
}

std::string HelpFormatter::make_description(const CLI::App* app) const {
  // CLI11's, with a newline at its end (a description ends with none).
  std::string description = CLI::Formatter::make_description(app);
  if (description.empty()) return description;
  description.pop_back();
  return wrapped(description, 0, width_, width_) + '\n';
}

std::string HelpFormatter::make_option(const CLI::Option* opt, bool is_positional) const {
  return two_columns(make_option_name(opt, is_positional) + make_option_opts(opt),
                     make_option_desc(opt));
}

std::string HelpFormatter::make_option_opts(const CLI::Option* opt) const {
  std::string opts = CLI::Formatter::make_option_opts(opt);
  // A validator's description after its type repeats the type: "FLOAT:FLOAT in [0 - 86400]".
  for (const std::string_view type : {"FLOAT", "INT", "UINT", "TEXT"}) {
    const std::string twice = " " + std::string(type) + ":" + std::string(type) + " ";
    for (std::size_t at = opts.find(twice); at != std::string::npos; at = opts.find(twice)) {
      opts.replace(at, twice.size(), " " + std::string(type) + " ");
    }
  }
  return opts;
}

std::string HelpFormatter::make_subcommand(const CLI::App* sub) const {
  return two_columns(sub->get_display_name(true), sub->get_description());
}

std::string HelpFormatter::make_footer(const CLI::App* app) const {
  const std::string footer = app->get_footer();
  if (footer.empty()) return footer;
  // A footer is paragraphs, reflowed to the width, and indented lines (a table of exit codes),
  // kept as written when they fit, else wrapped under their text: "  6  campaign: ..." under
  // "campaign".
  std::string out;
  std::string paragraph;
  auto end_paragraph = [&] {
    if (!paragraph.empty()) out += wrapped(paragraph, 0, width_, width_) + '\n';
    paragraph.clear();
  };
  std::size_t begin = 0;
  while (begin <= footer.size()) {
    std::size_t end = footer.find('\n', begin);
    if (end == std::string::npos) end = footer.size();
    const std::string_view line = std::string_view(footer).substr(begin, end - begin);
    begin = end + 1;
    if (!line.empty() && line.front() != ' ') {
      if (!paragraph.empty()) paragraph += ' ';
      paragraph += line;
      continue;
    }
    end_paragraph();
    if (line.size() <= width_) {
      out += std::string(line) + '\n';
      continue;
    }
    const std::size_t gap = line.find("  ", line.find_first_not_of(' '));
    const std::size_t text =
        gap == std::string_view::npos ? std::string_view::npos : line.find_first_not_of(' ', gap);
    const std::size_t hang = text == std::string_view::npos ? line.find_first_not_of(' ') : text;
    out += std::string(line.substr(0, hang)) +
           wrapped(line.substr(hang), hang, width_ - hang, width_) + '\n';
  }
  end_paragraph();
  return out;
}

std::size_t help_width() {
  const char* columns = std::getenv("COLUMNS");
  if (columns == nullptr) return 80;
  const std::string_view text(columns);
  std::size_t width = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), width);
  if (ec != std::errc() || end != text.data() + text.size() || width < 40 || width > 500) {
    return 80;
  }
  return width;
}

}  // namespace sewerplan::cli
