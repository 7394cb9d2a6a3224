// SPDX-License-Identifier: MIT
// Message text: how input text and numbers appear in diagnostics and error messages.
//
// A message quotes what the user wrote and compares values with limits; both must come out so that
// a person can act on them. Input text may hold control characters (a NUL in a name, the NULs of a
// UTF-16 file read as bytes, an escape sequence) that a terminal would act on or hide: they are
// shown escaped, as \x00 (and \u0085 for the C1 controls of UTF-8 text), and bytes that are not
// UTF-8 as \xE9. Numbers compared with a limit get as many significant digits as it takes to tell
// them apart: "step 0.305 m > 0.3", "at most 10000000 m, got 10000000.5", never "0.30 > 0.30".
//
//   d.error(where, "unknown shape " + input_quoted(field));       // 'ABC\x00'
//   const LimitText t = limit_text(0.3048, 0.3);                   // {"0.305", "0.3"}
//   d.error(where, "step " + t.value + " m > " + t.limit + " m");
//
// Thread safety: Pure functions: safe from any thread.
#pragma once

#include <string>
#include <string_view>

namespace sewerplan {

// `text` with every control character and every byte that is not UTF-8 escaped; the rest (printable
// ASCII and valid UTF-8) unchanged. Runtime: O(size).
std::string input_text(std::string_view text);

// input_text(text) in single quotes, cut after `max_bytes` bytes of input with "...".
std::string input_quoted(std::string_view text, std::size_t max_bytes = 80);

// `v` with `digits` significant digits, trailing zeros dropped, in plain decimals from 1e-4 to 1e15
// (the whole integer part kept: "0.3", "12.5", "10000000"), else with an exponent ("1e+16").
std::string number_text(double v, int digits = 6);

// A value and the limit it is compared with, each as number_text with the same number of
// significant digits: the fewest from `min_digits` on that print them differently (up to the 17
// that tell any two doubles apart). Equal values print the same.
struct LimitText {
  std::string value;
  std::string limit;
};
LimitText limit_text(double value, double limit, int min_digits = 3);

// The same in fixed notation, for reports printed with `decimals` decimals: more where those would
// show the two alike ("step 0.305 m > 0.300" for 0.3048 against 0.3, where 2 give "0.30 > 0.30").
LimitText limit_text_fixed(double value, double limit, int decimals = 2);

}  // namespace sewerplan
