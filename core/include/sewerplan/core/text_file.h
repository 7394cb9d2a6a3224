// SPDX-License-Identifier: MIT
// Whole-file text I/O with errors that name the file and the system's reason, and the text
// encodings that sewer files come in. Every text file is read through read_text_file, which
// skips a UTF-8 byte-order mark and decodes UTF-16 and UTF-32 with one, so that every reader
// (JSON maps and missions, SWMM, ISYBAU, the ASCII database, plans, risk tables, mappings) gets
// UTF-8 without a mark.
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

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/output_file.h"  // write_text_file: the one writer
#include "sewerplan/core/result.h"

namespace sewerplan {

// The file's text, without a byte-order mark (without_byte_order_mark): a UTF-16 file with one is
// UTF-8 here.
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

// The byte-order mark `text` begins with: its encoding ("UTF-8", "UTF-16LE", "UTF-16BE",
// "UTF-32LE", "UTF-32BE") and its size in bytes; none: an empty encoding and size 0.
struct ByteOrderMark {
  std::string_view encoding;
  std::size_t size = 0;
};
ByteOrderMark byte_order_mark(std::string_view text);

// `text` (read from `file`, for messages) in UTF-8 without its byte-order mark: UTF-8's is
// skipped, UTF-16 and UTF-32 text is decoded (iconv); without a mark, `text` unchanged. An error
// naming the file and the byte where the text is not what its mark says.
Result<std::string> without_byte_order_mark(std::string_view text, const std::string& file);

// How text_to_utf8 read a text.
enum class TextConversion {
  kNone,      // UTF-8 (or ASCII) as it is
  kDeclared,  // in the encoding the file declares, or its byte-order mark says
  kAssumed,   // not UTF-8 and nothing declared: `encoding` assumed (the caller warns)
};
struct TextDecoding {
  TextConversion conversion = TextConversion::kNone;
  std::string declared;      // what the file declared (empty if nothing)
  std::string encoding;      // what the text was read as: "UTF-8", "ISO-8859-15", "UTF-16LE", ...
  std::size_t replaced = 0;  // bytes that are no character in `encoding`: U+FFFD (the caller warns)
};

// A sewer file's text in UTF-8, decoded with iconv (glibc). A byte-order mark decides first
// (UTF-8's is skipped; UTF-16 and UTF-32 are decoded). Else `declared_encoding`, the encoding the
// file names (an XML declaration's, any case; empty if none): any encoding iconv knows
// (ISO-8859-1 to -16, Windows-1250 to -1258, UTF-16, ...; ISO-8859-1 and Latin-1 are read as
// Windows-1252, their superset of printable characters, as real exports labelled Latin-1 hold
// euro signs); one it does not know is an error naming `file` and the encoding. Undeclared text
// that is not valid UTF-8 is read as UTF-16 if its first characters are ASCII with NUL bytes
// between them, else as Windows-1252 (kAssumed). Line breaks are kept, so line numbers stay right.
Result<std::string> text_to_utf8(std::string_view text, std::string_view declared_encoding,
                                 const std::string& file, TextDecoding& how);

// `utf8` in `encoding` (a TextDecoding::encoding: "UTF-8", "WINDOWS-1252", "UTF-16LE", ...), for
// writing a file back in the encoding it was read in; without a byte-order mark. kUnsupportedFormat
// naming `file` if iconv does not know the encoding or a character has none in it. Runtime:
// O(size).
Result<std::string> utf8_to_text(std::string_view utf8, std::string_view encoding,
                                 const std::string& file);

// The warnings of a reader for `how`, at `file`: the encoding assumed, and bytes that were no
// character.
void warn_about_decoding(const TextDecoding& how, const std::string& file,
                         Diagnostics& diagnostics);

}  // namespace sewerplan
