// SPDX-License-Identifier: MIT
#include "sewerplan/core/message_text.h"

#include <string>

#include <gtest/gtest.h>

namespace sewerplan {
namespace {

// Issue 31: "step 0.30 m > 0.30" for a step of 0.3048 m; "at most 1e+07 m, got 1e+07".
TEST(MessageText, Issue31ShowsAValueApartFromTheLimitItBreaks) {
  EXPECT_EQ(limit_text(0.3048, 0.3).value, "0.305");
  EXPECT_EQ(limit_text(0.3048, 0.3).limit, "0.3");
  const LimitText far = limit_text(10000000.5, 1e7);
  EXPECT_EQ(far.value, "10000000.5");
  EXPECT_EQ(far.limit, "10000000");
  const LimitText close = limit_text(0.30000001, 0.3);
  EXPECT_NE(close.value, close.limit);
  EXPECT_EQ(close.value, "0.30000001");
  EXPECT_EQ(limit_text(0.3, 0.3).value, "0.3");  // equal values print the same
  EXPECT_EQ(limit_text(1e16, 1e5).value, "1e+16");
  EXPECT_EQ(limit_text(1e16, 1e5).limit, "100000");
  // Any two different doubles print differently.
  const double next = 0.1 + 0.2;
  EXPECT_NE(limit_text(next, 0.3).value, limit_text(next, 0.3).limit);
}

// Reports with fixed decimals keep them, and add what it takes to tell the two apart.
TEST(MessageText, Issue31FixedDecimalsAddWhatTellsAValueFromItsLimit) {
  EXPECT_EQ(limit_text_fixed(0.3048, 0.3).value, "0.305");
  EXPECT_EQ(limit_text_fixed(0.3048, 0.3).limit, "0.300");
  EXPECT_EQ(limit_text_fixed(116.5651, 90).value, "116.57");
  EXPECT_EQ(limit_text_fixed(116.5651, 90).limit, "90.00");
  EXPECT_EQ(limit_text_fixed(90.0000001, 90).value, "90.0000001");
}

TEST(MessageText, NumbersInPlainDecimalsWithinAUsualRange) {
  EXPECT_EQ(number_text(0), "0");
  EXPECT_EQ(number_text(-0.0), "0");
  EXPECT_EQ(number_text(12.5), "12.5");
  EXPECT_EQ(number_text(100000), "100000");
  EXPECT_EQ(number_text(1.0 / 3), "0.333333");
  EXPECT_EQ(number_text(-2.25, 2), "-2.2");  // round half to even of the binary value
  EXPECT_EQ(number_text(1e-9), "1e-09");
  EXPECT_EQ(number_text(1e300), "1e+300");
}

// Issue 31: a NUL in a name, the NULs of UTF-16 text read as bytes, an escape sequence: shown
// escaped, never sent raw to the terminal. UTF-8 letters stay as they are.
TEST(MessageText, Issue31EscapesControlCharactersAndBytesThatAreNotUtf8) {
  EXPECT_EQ(input_text(std::string("C\0"
                                   "3",
                                   3)),
            "C\\x003");
  EXPECT_EQ(input_text(std::string("[\0J\0", 4)), "[\\x00J\\x00");
  EXPECT_EQ(input_text("\x1b[31mred"), "\\x1B[31mred");
  EXPECT_EQ(input_text("tab\there\x7f"), "tab\\x09here\\x7F");
  EXPECT_EQ(input_text("Stra\xc3\x9f"
                       "e \xe2\x82\xac"),
            "Stra\xc3\x9f"
            "e \xe2\x82\xac");
  EXPECT_EQ(input_text("\xc2\x85"), "\\u0085");  // a C1 control in UTF-8
  EXPECT_EQ(input_text("Stra\xdf"
                       "e"),
            "Stra\\xDFe");                          // Latin-1, not UTF-8
  EXPECT_EQ(input_text("\xff\xfe"), "\\xFF\\xFE");  // a UTF-16 byte order mark
  EXPECT_EQ(input_quoted("abcdef", 3), "'abc...'");
  EXPECT_EQ(input_quoted("ab"), "'ab'");
}

}  // namespace
}  // namespace sewerplan
