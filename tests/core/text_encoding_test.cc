// SPDX-License-Identifier: MIT
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "sewerplan/core/ascii_case.h"
#include "sewerplan/core/text_file.h"

namespace sewerplan {
namespace {

TEST(AsciiCase, LowersAsciiLettersOnlyAndKeepsUtf8) {
  EXPECT_EQ(ascii_lower("Vw_QGEP_Reach.GPKG"), "vw_qgep_reach.gpkg");
  EXPECT_EQ(ascii_lower("@[`{09"), "@[`{09");  // the neighbours of 'A'..'Z' and 'a'..'z'
  EXPECT_EQ(ascii_lower("STRA\xc3\x9f"
                        "E \xc3\x84"),
            "stra\xc3\x9f"
            "e \xc3\x84");  // STRAßE Ä: the UTF-8 bytes unchanged
  EXPECT_EQ(ascii_lower(""), "");
}

TEST(TextEncoding, TellsValidUtf8FromEverythingElse) {
  EXPECT_TRUE(is_valid_utf8(""));
  EXPECT_TRUE(
      is_valid_utf8("S\xc3\xbc"
                    "d3"));                        // Süd3
  EXPECT_TRUE(is_valid_utf8("\xe2\x82\xac"));      // the euro sign
  EXPECT_TRUE(is_valid_utf8("\xf0\x9f\x98\x80"));  // U+1F600
  EXPECT_FALSE(
      is_valid_utf8("S\xfc"
                    "d3"));                         // Latin-1
  EXPECT_FALSE(is_valid_utf8("\xc0\xaf"));          // overlong '/'
  EXPECT_FALSE(is_valid_utf8("\xed\xa0\x80"));      // a surrogate
  EXPECT_FALSE(is_valid_utf8("\xf4\x90\x80\x80"));  // above U+10FFFF
  EXPECT_FALSE(is_valid_utf8("\xe2\x82"));          // truncated
}

TEST(TextEncoding, ReadsWindows1252AsUtf8) {
  EXPECT_EQ(windows1252_to_utf8("Stra\xdf"
                                "e"),
            "Stra\xc3\x9f"
            "e");                                          // Straße
  EXPECT_EQ(windows1252_to_utf8("\x80"), "\xe2\x82\xac");  // the euro sign
  EXPECT_EQ(windows1252_to_utf8("\x81"), "\xef\xbf\xbd");  // unassigned: U+FFFD
  EXPECT_TRUE(is_valid_utf8(windows1252_to_utf8(std::string(256, '\xff'))));
}

std::string utf8_of(std::string_view text, std::string_view declared, TextDecoding& how) {
  Result<std::string> utf8 = text_to_utf8(text, declared, "net.xml", how);
  EXPECT_TRUE(utf8.has_value()) << utf8.error().message;
  return utf8.has_value() ? *utf8 : std::string();
}

TEST(TextEncoding, ConvertsWhatIsDeclaredOrNotUtf8AndKeepsLines) {
  TextDecoding how;
  EXPECT_EQ(utf8_of("a\n\xfc\nb", "ISO-8859-1", how), "a\n\xc3\xbc\nb");
  EXPECT_EQ(how.conversion, TextConversion::kDeclared);
  EXPECT_EQ(utf8_of("a\n\xfc\nb", "", how), "a\n\xc3\xbc\nb");
  EXPECT_EQ(how.conversion, TextConversion::kAssumed);
  EXPECT_EQ(how.encoding, "WINDOWS-1252");
  EXPECT_EQ(utf8_of("S\xc3\xbc"
                    "d",
                    "utf-8", how),
            "S\xc3\xbc"
            "d");
  EXPECT_EQ(how.conversion, TextConversion::kNone);
}

// Issue 31: ISO-8859-15 was read as Latin-1 (its 0xA6 is Š, Latin-1's the broken bar); every
// encoding a declaration can name is decoded by iconv.
TEST(TextEncoding, Issue31DecodesTheDeclaredEncodingWithIconv) {
  TextDecoding how;
  EXPECT_EQ(utf8_of("\xa6"
                    "koda \xa4",
                    "ISO-8859-15", how),
            "\xc5\xa0koda \xe2\x82\xac");  // Škoda €
  EXPECT_EQ(how.encoding, "ISO-8859-15");
  EXPECT_EQ(utf8_of("\x8a\xb9", "windows-1250", how), "\xc5\xa0\xc4\x85");  // Šą
  EXPECT_EQ(utf8_of("\xe8\n", "ISO-8859-2", how), "\xc4\x8d\n");            // č
  EXPECT_EQ(utf8_of("\xc0", "KOI8-R", how), "\xd1\x8e");                    // ю
}

TEST(TextEncoding, Issue31AnUnknownDeclaredEncodingIsAnErrorNamingIt) {
  TextDecoding how;
  Result<std::string> utf8 = text_to_utf8("abc", "x-mac-klingon", "net.xml", how);
  ASSERT_FALSE(utf8.has_value());
  EXPECT_NE(utf8.error().message.find("net.xml: declares the text encoding 'x-mac-klingon', "
                                      "which sewerplan does not know"),
            std::string::npos)
      << utf8.error().message;
}

// Issue 31: a byte-order mark decides (UTF-8's is skipped, UTF-16's decoded); UTF-16 without a
// mark and without a declaration is told by its NUL bytes, and said to be assumed.
TEST(TextEncoding, Issue31ByteOrderMarksAndUndeclaredUtf16) {
  TextDecoding how;
  EXPECT_EQ(utf8_of("\xEF\xBB\xBF[TITLE]\n", "", how), "[TITLE]\n");
  EXPECT_EQ(utf8_of(std::string("\xFF\xFE[\0T\0\n\0\xFC\0", 10), "", how), "[T\n\xc3\xbc");
  EXPECT_EQ(how.conversion, TextConversion::kDeclared);
  EXPECT_EQ(utf8_of(std::string("\xFE\xFF\0[\0T", 6), "", how), "[T");
  EXPECT_EQ(utf8_of(std::string("<\0?\0x\0", 6), "", how), "<?x");
  EXPECT_EQ(how.conversion, TextConversion::kAssumed);
  EXPECT_EQ(how.encoding, "UTF-16LE");
  Diagnostics d;
  warn_about_decoding(how, "net.xml", d);
  ASSERT_EQ(d.all().size(), 1U);
  EXPECT_EQ(d.all()[0].message, "not UTF-8, and no encoding declared: read as UTF-16LE");
  // Decoded before (read_text_file): a declaration of UTF-16 on single-byte text is stale.
  EXPECT_EQ(utf8_of("<?xml version=\"1.0\" encoding=\"UTF-16\"?><a/>", "UTF-16", how),
            "<?xml version=\"1.0\" encoding=\"UTF-16\"?><a/>");
}

TEST(TextEncoding, Issue31ReadTextFileSkipsAUtf8MarkAndDecodesUtf16) {
  const auto path = std::filesystem::temp_directory_path() / "sewerplan-text-encoding-test.txt";
  std::ofstream(path, std::ios::binary) << "\xEF\xBB\xBF{}\n";
  EXPECT_EQ(*read_text_file(path), "{}\n");
  std::ofstream(path, std::ios::binary) << std::string("\xFF\xFE{\0}\0", 6);
  EXPECT_EQ(*read_text_file(path), "{}");
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace sewerplan
