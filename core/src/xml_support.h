// SPDX-License-Identifier: MIT
// Namespace-blind reading of XML elements with pugixml, and their paths for diagnostics. Private
// to core/src (pugixml is a private dependency of core: no pugixml type appears in a public
// header).
//
//   pugi::xml_node length = xml::child(kante, "Laenge");
//   std::string where = xml::path(length);  //
//   "/Identifikation/.../AbwassertechnischeAnlage[4]/Kante/Laenge"
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <pugixml.hpp>

#include "sewerplan/core/diagnostics.h"

namespace sewerplan::xml {

// An element's name without its namespace prefix ("Laenge" for "isy:Laenge").
std::string_view local_name(pugi::xml_node node);

// The first child element whose local name is `name`; an empty node if none.
pugi::xml_node child(pugi::xml_node node, std::string_view name);

// The element at the end of `names`, child by child; empty if any is missing.
pugi::xml_node descend(pugi::xml_node node, std::initializer_list<std::string_view> names);

// The element's text without surrounding white space.
std::string_view text(pugi::xml_node node);

// The element's path from the root, with local names and, where a parent has several children of
// that name, a 1-based index: "/Identifikation/Datenkollektive/.../AbwassertechnischeAnlage[3]".
// Runtime: O(depth x siblings); meant for error messages.
std::string path(pugi::xml_node node);

// The number in element `name` of `parent`, for `object` (a name for messages) in `file`. Missing
// or empty: an error naming the element when `required`, else nothing (real exports write empty
// optional elements). Not a number: an error at the element's path.
std::optional<double> number(pugi::xml_node parent, std::string_view name,
                             const std::string& object, bool required, const std::string& file,
                             Diagnostics& diagnostics);

// The number in element `name` of `parent`, for a value a reader can do without (it has a
// fallback): missing or empty is none; not a number is a warning at the element ("... is not a
// number: '3OO': ignored") and none. Real exports write such values by hand.
std::optional<double> optional_number(pugi::xml_node parent, std::string_view name,
                                      const std::string& object, const std::string& file,
                                      Diagnostics& diagnostics);

// The line of byte `offset` in `text`, from 1.
std::uint32_t line_of_offset(std::string_view text, std::ptrdiff_t offset);

// The encoding named by the XML declaration at the start of `text` ("ISO-8859-1"); empty if none.
std::string_view declared_encoding(std::string_view text);

// Parses `text` into `doc` in UTF-8. The text is decoded first by its byte-order mark or declared
// encoding (text_to_utf8, text_file.h: any encoding iconv knows; undeclared text that is not
// UTF-8 with a warning naming the encoding assumed), so names keep their letters and an error's
// line is the line in the file. An unknown declared encoding, or XML that is not well-formed
// (at its line), is an error: false.
bool load_utf8(pugi::xml_document& doc, std::string_view text, const std::string& file_name,
               Diagnostics& diagnostics);

// For a root element of another sewer exchange format, a message naming it: DWA-M 150 (root
// <DATA>, the DWA's format) or an INTERLIS transfer file (root <TRANSFER>: SIA405 Abwasser,
// VSA-KEK).
std::optional<std::string> foreign_sewer_format(pugi::xml_node root);

}  // namespace sewerplan::xml
