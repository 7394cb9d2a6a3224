// SPDX-License-Identifier: MIT
// Whole-file text I/O with errors that name the file and the system's reason, and the text
// encodings that sewer files come in.
//
// sewerplan works in UTF-8 throughout: every name in a map may end up in JSON output, which must
// be UTF-8. Sewer databases are often exported in Latin-1 (ISO 8859-1) or Windows-1252, so the
// importers (SWMM, ISYBAU, the ASCII database) convert such text with text_to_utf8() before
// reading it; MapBuilder rejects a name that is still not valid UTF-8.
//
//   Result<std::string> text = read_text_file("ais.json");
//   if (!text.has_value()) std::cerr << text.error().message;  // "cannot read ais.json: No such
//   ..."
//
// Thread safety: The functions share nothing: call them from any number of threads (not on the same
// file at once).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "sewerplan/core/output_file.h"  // write_text_file: the one writer
#include "sewerplan/core/result.h"

namespace sewerplan {

Result<std::string> read_text_file(const std::filesystem::path& path);

// Whether `text` is well-formed UTF-8 (no overlong forms, surrogates or code points above
// U+10FFFF). Runtime: O(size).
bool is_valid_utf8(std::string_view text);

// `text`, read as Windows-1252, in UTF-8. Windows-1252 is Latin-1 with printable characters
// (the euro sign, typographic quotes) in place of the C1 controls 0x80..0x9F, so it reads Latin-1
// text alike; its five unassigned bytes become U+FFFD.
std::string windows1252_to_utf8(std::string_view text);

// `text` unchanged if it is valid UTF-8, else read as Windows-1252: for names in messages.
std::string to_utf8_lossy(std::string_view text);

// What text_to_utf8 did.
enum class TextConversion { kNone, kDeclaredLatin1, kUndeclaredLatin1 };

// A sewer file's text in UTF-8. `declared_encoding` is the encoding the file names (an XML
// declaration's, lower or upper case; empty if none): ISO-8859-1, Latin-1 and Windows-1252 are
// converted. Otherwise text that is not valid UTF-8 is taken for Windows-1252 and converted
// (kUndeclaredLatin1: the caller warns). Line breaks are kept, so line numbers stay right.
std::string text_to_utf8(std::string_view text, std::string_view declared_encoding,
                         TextConversion& conversion);

}  // namespace sewerplan
