// SPDX-License-Identifier: MIT
#include "sewerplan/core/map_ascii.h"

#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sewerplan/core/map_builder.h"
#include "sewerplan/core/rng.h"

namespace sewerplan {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// Every feature of the format, written the way a person might: comments, tabs, keys in any order,
// defaults left out, a CRLF line, '#' inside a name.
const std::string kHandWritten =
    "# AIS test bed, by hand\n"
    "   # an indented comment\n"
    "\n"
    "sewerdb 1   # the format version\n"
    "map ais-testbed\r\n"
    "manhole M1 diameter=1.2 exit x=0 y=0      # z left out: 0\n"
    "\tslot P1 azimuth=0                       # invert left out: the manhole's z\n"
    "manhole M2 x=8.5 y=0 z=-0.25 diameter=1 variant=B\n"
    "  slot P1 azimuth=180 invert=-0.2\n"
    "  slot P2 invert=-0.25 azimuth=0\n"
    "  slot S1 azimuth=90\n"
    "manhole M3 x=20 y=-1.5e1 z=-0.5 diameter=0.8 exit\n"
    "  slot P2 azimuth=-90\n"
    "manhole x#y x=1 y=1 diameter=1\n"
    "  slot S2 azimuth=45 invert=0.1\n"
    "\n"
    "pipe P1 from=M1 to=M2 length=8.5 diameter=0.6\n"
    "pipe P2 from=M2 to=M3 length=12 diameter=0.4 shape=egg height=0.6 risk=0.25\n"
    "pipe S1 to=- from=M2 length=2 diameter=0.3 shape=rectangular height=0.5\n"
    "pipe S2 from=- to=x#y length=1 diameter=0.2 height=0.25\n"
    "point W1 pipe=P2 offset=2.5\n"
    "point W2 pipe=P1 offset=0\n";

const std::string kCanonical =
    "# sewerplan ASCII sewer database; format: docs/formats/ascii-database.md\n"
    "sewerdb 1\n"
    "map ais-testbed\n"
    "manhole M1 x=0 y=0 z=0 diameter=1.2 exit\n"
    "  slot P1 azimuth=0 invert=0\n"
    "manhole M2 x=8.5 y=0 z=-0.25 diameter=1 variant=B\n"
    "  slot P1 azimuth=180 invert=-0.2\n"
    "  slot P2 azimuth=0 invert=-0.25\n"
    "  slot S1 azimuth=90 invert=-0.25\n"
    "manhole M3 x=20 y=-15 z=-0.5 diameter=0.8 exit\n"
    "  slot P2 azimuth=-90 invert=-0.5\n"
    "manhole x#y x=1 y=1 z=0 diameter=1\n"
    "  slot S2 azimuth=45 invert=0.1\n"
    "\n"
    "pipe P1 from=M1 to=M2 length=8.5 diameter=0.6\n"
    "pipe P2 from=M2 to=M3 length=12 diameter=0.4 shape=egg height=0.6 risk=0.25\n"
    "pipe S1 from=M2 to=- length=2 diameter=0.3 shape=rectangular height=0.5\n"
    "pipe S2 from=- to=x#y length=1 diameter=0.2 height=0.25\n"
    "\n"
    "point W1 pipe=P2 offset=2.5\n"
    "point W2 pipe=P1 offset=0\n";

SewerMap read_ok(const std::string& text, const std::string& file = "maps/t.sewer") {
  Diagnostics d;
  Result<SewerMap> map = read_map_ascii(text, file, d);
  EXPECT_TRUE(map.has_value()) << (map.has_value() ? "" : map.error().message);
  EXPECT_FALSE(d.has_errors());
  return map.has_value() ? std::move(map).value() : SewerMap();
}

std::string write_ok(const SewerMap& map) {
  std::ostringstream out;
  Result<void> written = write_map_ascii(map, out);
  EXPECT_TRUE(written.has_value()) << (written.has_value() ? "" : written.error().message);
  return out.str();
}

// The error message of reading `text` from maps/t.sewer, which must fail with `code`.
std::string read_error(const std::string& text, ErrorCode code = ErrorCode::kParse) {
  Diagnostics d;
  Result<SewerMap> map = read_map_ascii(text, "maps/t.sewer", d);
  EXPECT_FALSE(map.has_value());
  if (map.has_value()) return {};
  EXPECT_EQ(map.error().code, code);
  return map.error().message;
}

TEST(MapAscii, ReadsEveryFeatureAndWritesTheCanonicalText) {
  const SewerMap map = read_ok(kHandWritten);
  EXPECT_EQ(map.name(), "ais-testbed");
  EXPECT_EQ(map.manhole_count(), 4U);
  EXPECT_EQ(map.pipe_count(), 4U);
  EXPECT_EQ(map.point_count(), 2U);
  EXPECT_EQ(write_ok(map), kCanonical);
}

TEST(MapAscii, ReadsTheCanonicalTextBackToAnEqualMap) {
  const SewerMap map = read_ok(kHandWritten);
  const SewerMap again = read_ok(kCanonical);
  EXPECT_EQ(again, map);
  EXPECT_EQ(write_ok(again), kCanonical);
}

TEST(MapAscii, WritingThenReadingKeepsEveryNumberExactly) {
  MapBuilder b("exact");
  b.add_manhole({.name = "A",
                 .position = {0.1 + 0.2, 1.0 / 3.0, -1e-7},
                 .diameter_m = 99.999999999999986,  // within core/limits.h
                 .variant = 'Z',
                 .slots = {{.pipe = "P", .azimuth_deg = 359.99999999999994, .invert_z_m = -0.0}}});
  b.add_manhole({.name = "B",
                 .position = {1234567.891234567, -2.2250738585072014e-308, 5e-324},
                 .diameter_m = 0.7,
                 .exit = true,
                 .slots = {{.pipe = "P", .azimuth_deg = -180, .invert_z_m = 2.0 / 3.0}}});
  b.add_pipe({.name = "P",
              .from = "A",
              .to = "B",
              .length_m = 1.0 / 7.0,
              .diameter_m = 0.1,
              .shape = PipeShape::kOther,
              .height_m = 0.30000000000000004,
              .blockage_risk = 1.0F / 3.0F});
  b.add_point({.name = "W", .pipe = "P", .offset_m = 1.0 / 14.0});
  Diagnostics d;
  Result<SewerMap> map = std::move(b).build(d);
  ASSERT_TRUE(map.has_value()) << map.error();
  const std::string text = write_ok(*map);
  EXPECT_EQ(read_ok(text, "exact.sewer"), *map) << text;
}

TEST(MapAscii, ReadsBlindEndsAsPipeEndsWithoutAManhole) {
  const SewerMap map = read_ok(kCanonical);
  const Pipe& s1 = map.pipe(*map.find_pipe("S1"));
  EXPECT_EQ(s1.ends[0].manhole, map.find_manhole("M2"));
  EXPECT_FALSE(s1.ends[1].manhole.has_value());
  const Pipe& s2 = map.pipe(*map.find_pipe("S2"));
  EXPECT_FALSE(s2.ends[0].manhole.has_value());
  EXPECT_EQ(s2.ends[1].manhole, map.find_manhole("x#y"));
}

TEST(MapAscii, FillsInTheDocumentedDefaults) {
  const SewerMap map = read_ok(
      "sewerdb 1\n"
      "manhole M1 diameter=1 z=2\n"
      "  slot P1 azimuth=0\n"
      "manhole M2 diameter=1\n"
      "  slot P1 azimuth=180 invert=1.5\n"
      "pipe P1 from=M1 to=M2 length=3 diameter=0.5\n",
      "some/dir/defaults.sewer");
  EXPECT_EQ(map.name(), "defaults");  // the file's stem
  const ManholeId m1 = *map.find_manhole("M1");
  EXPECT_EQ(map.manhole(m1).position, (Position{0, 0, 2}));
  EXPECT_FALSE(map.manhole(m1).exit);
  EXPECT_FALSE(map.manhole(m1).variant.has_value());
  EXPECT_EQ(map.slots(m1)[0].invert_z_m, 2.0);  // the manhole's z
  EXPECT_EQ(map.slots(*map.find_manhole("M2"))[0].invert_z_m, 1.5);
  const Pipe& p1 = map.pipe(*map.find_pipe("P1"));
  EXPECT_EQ(p1.shape, PipeShape::kCircular);
  EXPECT_EQ(p1.height_m, 0.5);  // the diameter
  EXPECT_FALSE(p1.blockage_risk.has_value());
}

TEST(MapAscii, GivesSlotsToTheMostRecentManholeLineInTheirOrder) {
  const SewerMap map = read_ok(
      "sewerdb 1\n"
      "manhole M1 diameter=1\n"
      "  slot P1 azimuth=0\n"
      "manhole M2 diameter=1\n"
      "pipe P1 from=M1 to=M2 length=3 diameter=0.5\n"
      "pipe P2 from=M2 to=- length=3 diameter=0.5\n"
      "  slot P2 azimuth=90\n"
      "  slot P1 azimuth=180\n");
  const auto slots = map.slots(*map.find_manhole("M2"));
  ASSERT_EQ(slots.size(), 2U);
  EXPECT_EQ(slots[0].pipe, map.find_pipe("P2"));
  EXPECT_EQ(slots[1].pipe, map.find_pipe("P1"));
}

struct SyntaxCase {
  std::string name;
  std::string text;
  std::string expected;  // a whole line of the error message: "file:line: error: what"
};

// Names the case in test output instead of dumping its bytes.
void PrintTo(const SyntaxCase& syntax_case, std::ostream* os) { *os << syntax_case.name; }

class MapAsciiSyntaxError : public ::testing::TestWithParam<SyntaxCase> {};

TEST_P(MapAsciiSyntaxError, IsReportedWithFileLineObjectAndKey) {
  EXPECT_THAT(read_error(GetParam().text), HasSubstr(GetParam().expected));
}

const std::string kHeader = "sewerdb 1\n";
const std::string kPipeStart = kHeader + "pipe P5 from=M1 to=M2 ";

INSTANTIATE_TEST_SUITE_P(
    EveryCase, MapAsciiSyntaxError,
    ::testing::Values(
        SyntaxCase{"MissingHeader", "manhole M1 diameter=1\n",
                   "maps/t.sewer:1: error: missing header: the first line must be 'sewerdb 1'"},
        SyntaxCase{"UnsupportedVersion", "# v2\nsewerdb 2\n",
                   "maps/t.sewer:2: error: unsupported sewerdb version 2, this reader knows "
                   "version 1"},
        SyntaxCase{"MissingVersion", "sewerdb\n",
                   "maps/t.sewer:1: error: sewerdb: missing format version"},
        SyntaxCase{"HeaderTwice", kHeader + "sewerdb 1\n",
                   "maps/t.sewer:2: error: the header 'sewerdb 1' may only be the first line"},
        SyntaxCase{"UnknownKeyword", kHeader + "manhol M1 diameter=1\n",
                   "maps/t.sewer:2: error: unknown keyword 'manhol'"},
        SyntaxCase{"SlotBeforeAnyManhole", kHeader + "slot P1 azimuth=0\n",
                   "maps/t.sewer:2: error: slot P1: comes before any manhole line"},
        SyntaxCase{"UnknownKey", kPipeStart + "lenght=3 diameter=1\n",
                   "maps/t.sewer:2: error: pipe P5: unknown key 'lenght'"},
        SyntaxCase{"MissingRequiredKey", kPipeStart + "length=3\n",
                   "maps/t.sewer:2: error: pipe P5: missing required key 'diameter'"},
        SyntaxCase{"MissingSlotKey", kHeader + "manhole M1 diameter=1\n  slot P1 invert=0\n",
                   "maps/t.sewer:3: error: manhole M1 slot P1: missing required key 'azimuth'"},
        SyntaxCase{"KeyGivenTwice", kHeader + "manhole M1 diameter=1 diameter=2\n",
                   "maps/t.sewer:2: error: manhole M1: key 'diameter' is given twice"},
        SyntaxCase{"NumberWithTrailingGarbage", kPipeStart + "length=1.5m diameter=1\n",
                   "maps/t.sewer:2: error: pipe P5: length '1.5m' is not a number"},
        SyntaxCase{"NumberWithPlusSign", kPipeStart + "length=+1 diameter=1\n",
                   "maps/t.sewer:2: error: pipe P5: length '+1' is not a number"},
        SyntaxCase{"NotANumberAtAll", kPipeStart + "length=3 diameter=wide\n",
                   "maps/t.sewer:2: error: pipe P5: diameter 'wide' is not a number"},
        SyntaxCase{"NaN", kPipeStart + "length=nan diameter=1\n",
                   "maps/t.sewer:2: error: pipe P5: length 'nan' is not a finite number"},
        SyntaxCase{"Infinity", kHeader + "manhole M1 diameter=1 y=-inf\n",
                   "maps/t.sewer:2: error: manhole M1: y '-inf' is not a finite number"},
        SyntaxCase{"OutOfRange", kHeader + "manhole M1 diameter=1 x=1e999\n",
                   "maps/t.sewer:2: error: manhole M1: x '1e999' is out of range"},
        SyntaxCase{"MissingName", kHeader + "manhole diameter=1\n",
                   "maps/t.sewer:2: error: manhole: missing name"},
        SyntaxCase{"MissingNameAtEndOfLine", kHeader + "point   # W1\n",
                   "maps/t.sewer:2: error: point: missing name"},
        SyntaxCase{"MapGivenTwice", kHeader + "map a\nmap b\n",
                   "maps/t.sewer:3: error: map b: the map name is given twice (first at "
                   "maps/t.sewer:2)"},
        SyntaxCase{"MapAfterObjects", kHeader + "manhole M1 diameter=1\nmap a\n",
                   "maps/t.sewer:3: error: map a: the map name must come before the first "
                   "manhole, pipe or point"},
        SyntaxCase{"MapNameWithControlCharacter", kHeader + "map a\vb\n",
                   "maps/t.sewer:2: error: map a\vb: the name cannot be read"},
        SyntaxCase{"BareTokenThatIsNotAFlag", kHeader + "manhole M1 diameter=1 exitt\n",
                   "maps/t.sewer:2: error: manhole M1: unexpected token 'exitt'"},
        SyntaxCase{"KeyWithoutValue", kHeader + "manhole M1 diameter\n",
                   "maps/t.sewer:2: error: manhole M1: key 'diameter' needs a value"},
        SyntaxCase{"EmptyValue", kPipeStart + "length= diameter=1\n",
                   "maps/t.sewer:2: error: pipe P5: empty value for key 'length'"},
        SyntaxCase{"FlagWithValue", kHeader + "manhole M1 diameter=1 exit=yes\n",
                   "maps/t.sewer:2: error: manhole M1: 'exit' is a flag and takes no value"},
        SyntaxCase{"UnknownShape", kPipeStart + "length=1 diameter=1 shape=round\n",
                   "maps/t.sewer:2: error: pipe P5: unknown shape 'round'"},
        SyntaxCase{"LowerCaseVariant", kHeader + "manhole M1 diameter=1 variant=b\n",
                   "maps/t.sewer:2: error: manhole M1: variant must be one capital letter A..Z, "
                   "got 'b'"},
        SyntaxCase{"ManholeNamedLikeABlindEnd", kHeader + "manhole - diameter=1\n",
                   "maps/t.sewer:2: error: manhole -: the name '-' is reserved for blind pipe "
                   "ends"}),
    [](const ::testing::TestParamInfo<SyntaxCase>& case_info) { return case_info.param.name; });

TEST(MapAscii, ReportsAnEmptyFileAsMissingItsHeader) {
  EXPECT_THAT(read_error(""), HasSubstr("maps/t.sewer: error: missing header 'sewerdb 1'"));
  EXPECT_THAT(read_error("# only a comment\n\n"), HasSubstr("missing header"));
}

TEST(MapAscii, ReportsSeveralSyntaxErrorsInOnePassWithoutBuilding) {
  Diagnostics d;
  Result<SewerMap> map = read_map_ascii(
      "sewerdb 1\n"
      "manhole M1 diameter=1 colour=red\n"
      "  slot P1 azimuth=north\n"
      "pipe P1 from=M1 to=- length=1\n"
      "pipe P2 from=M1 to=M9 length=1 diameter=1\n"
      "frobnicate\n",
      "maps/t.sewer", d);
  ASSERT_FALSE(map.has_value());
  EXPECT_EQ(map.error().code, ErrorCode::kParse);
  EXPECT_EQ(d.error_count(), 4U);
  const std::string& msg = map.error().message;
  EXPECT_THAT(msg, HasSubstr("maps/t.sewer:2: error: manhole M1: unknown key 'colour'"));
  EXPECT_THAT(msg, HasSubstr("maps/t.sewer:3: error: manhole M1 slot P1: azimuth 'north' is not"));
  EXPECT_THAT(msg, HasSubstr("maps/t.sewer:4: error: pipe P1: missing required key 'diameter'"));
  EXPECT_THAT(msg, HasSubstr("maps/t.sewer:6: error: unknown keyword 'frobnicate'"));
  EXPECT_THAT(msg, Not(HasSubstr("M9")));  // the network is not checked
}

TEST(MapAscii, StopsAtTheFirstLineOfAnotherVersionOrFormat) {
  Diagnostics v2;
  EXPECT_FALSE(read_map_ascii("sewerdb 2\nwhatever 3\nmore\n", "t.sewer", v2).has_value());
  EXPECT_EQ(v2.error_count(), 1U);
  Diagnostics json;
  EXPECT_FALSE(read_map_ascii("{\n  \"manholes\": []\n}\n", "t.sewer", json).has_value());
  EXPECT_EQ(json.error_count(), 1U);
  EXPECT_EQ(json.all()[0].where, "t.sewer:1");
}

TEST(MapAscii, ReportsNetworkErrorsAtTheLineOfTheirRecord) {
  const std::string msg = read_error(
      "sewerdb 1\n"
      "manhole M1 diameter=1\n"
      "  slot P1 azimuth=0\n"
      "  slot P9 azimuth=90\n"
      "pipe P1 from=M1 to=M7 length=5 diameter=0.5\n"
      "point W1 pipe=P1 offset=6\n",
      ErrorCode::kInvalidMap);
  EXPECT_THAT(msg, HasSubstr("maps/t.sewer:4: error: manhole M1 slot 2 names unknown pipe 'P9'"));
  EXPECT_THAT(msg, HasSubstr("maps/t.sewer:5: error: pipe P1: to names unknown manhole 'M7'"));
  EXPECT_THAT(msg, HasSubstr("maps/t.sewer:6: error: inspection point W1: offset 6 m is outside"));
}

TEST(MapAscii, ReportsBuilderWarningsAtTheLineOfTheirRecord) {
  Diagnostics d;
  Result<SewerMap> map = read_map_ascii(kHeader + "\nmanhole M1 diameter=1\n", "t.sewer", d);
  ASSERT_TRUE(map.has_value());
  ASSERT_EQ(d.warning_count(), 1U);
  EXPECT_EQ(d.all()[0].where, "t.sewer:3");
  EXPECT_THAT(d.all()[0].message, HasSubstr("manhole M1 has no pipes"));
}

TEST(MapAscii, RefusesToWriteNamesThatCannotBeReadBack) {
  MapBuilder b("ais testbed");
  b.add_manhole({.name = "#M1", .diameter_m = 1, .slots = {{.pipe = "a=b"}}});
  b.add_manhole({.name = "-", .diameter_m = 1, .slots = {{.pipe = "a=b"}}});
  b.add_pipe({.name = "a=b", .from = "#M1", .to = "-", .length_m = 1, .diameter_m = 0.5});
  Diagnostics d;
  Result<SewerMap> map = std::move(b).build(d);
  ASSERT_TRUE(map.has_value()) << map.error();
  std::ostringstream out;
  Result<void> written = write_map_ascii(*map, out);
  ASSERT_FALSE(written.has_value());
  EXPECT_EQ(written.error().code, ErrorCode::kInvalidArgument);
  const std::string& msg = written.error().message;
  EXPECT_THAT(msg, HasSubstr("map name 'ais testbed' cannot be written: it contains white space"));
  EXPECT_THAT(msg, HasSubstr("manhole '#M1' cannot be written: it starts with '#'"));
  EXPECT_THAT(msg, HasSubstr("manhole '-' cannot be written: '-' stands for a blind pipe end"));
  EXPECT_THAT(msg, HasSubstr("pipe 'a=b' cannot be written: it contains '='"));
  EXPECT_EQ(out.str(), "");
}

TEST(MapAscii, ReportsAFailingStream) {
  std::ostringstream out;
  out.setstate(std::ios::badbit);
  Result<void> written = write_map_ascii(read_ok(kCanonical), out);
  ASSERT_FALSE(written.has_value());
  EXPECT_EQ(written.error().code, ErrorCode::kIo);
}

// Reading any text gives a map or an error, never a crash; and a map read always writes and reads
// back to an equal map.
void expect_total_and_round_trips(const std::string& text) {
  Diagnostics d;
  Result<SewerMap> map = read_map_ascii(text, "fuzz.sewer", d);
  if (!map.has_value()) {
    EXPECT_TRUE(map.error().code == ErrorCode::kParse || map.error().code == ErrorCode::kInvalidMap)
        << map.error();
    EXPECT_TRUE(d.has_errors());
    return;
  }
  EXPECT_FALSE(d.has_errors());
  std::ostringstream out;
  Result<void> written = write_map_ascii(*map, out);
  ASSERT_TRUE(written.has_value()) << written.error() << "\nfor input:\n" << text;
  Diagnostics again_d;
  Result<SewerMap> again = read_map_ascii(out.str(), "fuzz.sewer", again_d);
  ASSERT_TRUE(again.has_value()) << again.error() << "\nfor input:\n" << text;
  EXPECT_EQ(*again, *map) << "input:\n" << text << "\nwritten:\n" << out.str();
}

TEST(MapAscii, SurvivesEveryTruncationOfAValidFile) {
  for (const std::string& text : {kHandWritten, kCanonical}) {
    for (std::size_t n = 0; n <= text.size(); ++n) expect_total_and_round_trips(text.substr(0, n));
  }
}

TEST(MapAscii, SurvivesRandomBytesTokensAndMutations) {
  const std::vector<std::string> vocabulary = {
      "sewerdb", "1",    "map",      "manhole", "slot",  "pipe",
      "point",   "exit", "M1",       "M2",      "P1",    "-",
      "=",       "x=",   "diameter", "from=",   "to=",   "length=",
      "azimuth", "0.5",  "1e9",      "nan",     "-0",    "#",
      " ",       "\t",   "\n",       "\r",      "\r\n",  std::string(1, '\0'),
      "\xff",    "==",   "shape=",   "egg",     "risk=", "variant="};
  Rng rng(20040901);
  for (int round = 0; round < 1000; ++round) {
    std::string bytes(rng.below(120), '\0');
    for (char& c : bytes) c = static_cast<char>(rng.below(256));
    expect_total_and_round_trips(bytes);
    expect_total_and_round_trips(kHeader + bytes);

    std::string tokens = kHeader;
    const std::uint64_t count = rng.below(60);
    for (std::uint64_t i = 0; i < count; ++i) tokens += vocabulary[rng.below(vocabulary.size())];
    expect_total_and_round_trips(tokens);

    std::string mutated = kCanonical;
    for (std::uint64_t i = rng.below(4) + 1; i > 0 && !mutated.empty(); --i) {
      const std::size_t at = rng.below(mutated.size());
      if (rng.bernoulli(0.5)) {
        mutated[at] = static_cast<char>(rng.below(256));
      } else {
        mutated.erase(at, rng.below(8));
      }
    }
    expect_total_and_round_trips(mutated);
  }
}

}  // namespace
}  // namespace sewerplan
