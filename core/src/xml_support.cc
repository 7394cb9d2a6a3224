// SPDX-License-Identifier: MIT
#include "xml_support.h"

#include <algorithm>
#include <vector>

#include "sewerplan/core/text_file.h"

#include "ascii_syntax.h"

namespace sewerplan::xml {

std::string_view local_name(pugi::xml_node node) {
  const std::string_view name = node.name();
  const std::size_t colon = name.find(':');
  return colon == std::string_view::npos ? name : name.substr(colon + 1);
}

pugi::xml_node child(pugi::xml_node node, std::string_view name) {
  for (pugi::xml_node c = node.first_child(); c; c = c.next_sibling()) {
    if (c.type() == pugi::node_element && local_name(c) == name) return c;
  }
  return {};
}

pugi::xml_node descend(pugi::xml_node node, std::initializer_list<std::string_view> names) {
  for (std::string_view name : names) {
    if (!node) break;
    node = child(node, name);
  }
  return node;
}

std::string_view text(pugi::xml_node node) {
  std::string_view t = node.child_value();
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!t.empty() && blank(t.front())) t.remove_prefix(1);
  while (!t.empty() && blank(t.back())) t.remove_suffix(1);
  return t;
}

std::string path(pugi::xml_node node) {
  std::vector<std::string> parts;
  for (; node && node.type() == pugi::node_element; node = node.parent()) {
    const std::string_view name = local_name(node);
    std::size_t index = 0;
    std::size_t same = 0;
    for (pugi::xml_node s = node.parent().first_child(); s; s = s.next_sibling()) {
      if (s.type() != pugi::node_element || local_name(s) != name) continue;
      ++same;
      if (s == node) index = same;
    }
    std::string part(name);
    if (same > 1) part += "[" + std::to_string(index) + "]";
    parts.push_back(std::move(part));
  }
  std::string out;
  for (auto it = parts.rbegin(); it != parts.rend(); ++it) out += "/" + *it;
  return out;
}

std::uint32_t line_of_offset(std::string_view text, std::ptrdiff_t offset) {
  const std::size_t end =
      std::min(text.size(), static_cast<std::size_t>(std::max<std::ptrdiff_t>(offset, 0)));
  return static_cast<std::uint32_t>(
      1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(end), '\n'));
}

std::string_view declared_encoding(std::string_view text) {
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
  if (!text.starts_with("<?xml")) return {};
  const std::string_view declaration = text.substr(0, text.find("?>"));
  const std::size_t at = declaration.find("encoding");
  if (at == std::string_view::npos) return {};
  std::string_view rest = declaration.substr(at + 8);
  while (!rest.empty() && (rest.front() == ' ' || rest.front() == '=')) rest.remove_prefix(1);
  if (rest.empty() || (rest.front() != '"' && rest.front() != '\'')) return {};
  const char quote = rest.front();
  rest.remove_prefix(1);
  return rest.substr(0, rest.find(quote));
}

bool load_utf8(pugi::xml_document& doc, std::string_view text, const std::string& file_name,
               Diagnostics& diagnostics) {
  TextDecoding how;
  Result<std::string> utf8 = text_to_utf8(text, declared_encoding(text), file_name, how);
  if (!utf8.has_value()) {
    std::string_view message = utf8.error().message;
    if (message.starts_with(file_name + ": ")) message.remove_prefix(file_name.size() + 2);
    diagnostics.error(file_name, std::string(message));
    return false;
  }
  warn_about_decoding(how, file_name, diagnostics);
  const pugi::xml_parse_result parsed =
      doc.load_buffer(utf8->data(), utf8->size(), pugi::parse_default, pugi::encoding_utf8);
  if (!parsed) {
    diagnostics.error(file_name + ":" + std::to_string(line_of_offset(*utf8, parsed.offset)),
                      std::string("XML is not well-formed: ") + parsed.description());
    return false;
  }
  return true;
}

std::optional<std::string> foreign_sewer_format(pugi::xml_node root) {
  const std::string_view name = local_name(root);
  if (name == "DATA" || name == "M150" || name == "M145") {
    return "a DWA-M 150 file (root <" + std::string(name) +
           ">, the DWA's exchange format): sewerplan reads ISYBAU XML, not DWA-M 150; export the "
           "network as ISYBAU XML";
  }
  if (name == "TRANSFER") {
    return std::string(
        "an INTERLIS transfer file (root <TRANSFER>: SIA405 Abwasser or VSA-KEK): sewerplan "
        "reads ISYBAU XML, not INTERLIS; export the network as ISYBAU XML");
  }
  return std::nullopt;
}

std::optional<double> number(pugi::xml_node parent, std::string_view name,
                             const std::string& object, bool required, const std::string& file,
                             Diagnostics& diagnostics) {
  const pugi::xml_node n = child(parent, name);
  const std::string_view t = text(n);
  if (t.empty()) {
    if (required)
      diagnostics.error(file + ":" + path(parent), object + ": no " + std::string(name));
    return std::nullopt;
  }
  double v = 0;
  if (ascii_syntax::parse_number(t, v) != ascii_syntax::NumberError::kNone) {
    diagnostics.error(file + ":" + path(n), object + ": " + std::string(name) +
                                                " is not a number: " + ascii_syntax::quoted(t));
    return std::nullopt;
  }
  return v;
}

std::optional<double> optional_number(pugi::xml_node parent, std::string_view name,
                                      const std::string& object, const std::string& file,
                                      Diagnostics& diagnostics) {
  const pugi::xml_node n = child(parent, name);
  const std::string_view t = text(n);
  if (t.empty()) return std::nullopt;
  double v = 0;
  if (ascii_syntax::parse_number(t, v) != ascii_syntax::NumberError::kNone) {
    diagnostics.warning(file + ":" + path(n), object + ": " + std::string(name) +
                                                  " is not a number: " + ascii_syntax::quoted(t) +
                                                  ": ignored");
    return std::nullopt;
  }
  return v;
}

}  // namespace sewerplan::xml
