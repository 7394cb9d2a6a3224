// SPDX-License-Identifier: MIT
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

TEST(TextEncoding, ConvertsWhatIsDeclaredOrNotUtf8AndKeepsLines) {
  TextConversion how = TextConversion::kNone;
  EXPECT_EQ(text_to_utf8("a\n\xfc\nb", "ISO-8859-1", how), "a\n\xc3\xbc\nb");
  EXPECT_EQ(how, TextConversion::kDeclaredLatin1);
  EXPECT_EQ(text_to_utf8("a\n\xfc\nb", "", how), "a\n\xc3\xbc\nb");
  EXPECT_EQ(how, TextConversion::kUndeclaredLatin1);
  EXPECT_EQ(text_to_utf8("S\xc3\xbc"
                         "d",
                         "utf-8", how),
            "S\xc3\xbc"
            "d");
  EXPECT_EQ(how, TextConversion::kNone);
}

}  // namespace
}  // namespace sewerplan
