// SPDX-License-Identifier: MIT
// parse_plan and validate_plan on broken input: truncations, random bytes, shuffled tokens. They
// must never crash (the sanitizer build checks memory too), and a plan that parses must validate
// to a report and format back to text that parses to the same plan.
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sewerplan/core/rng.h"
#include "sewerplan/domain/plan_text.h"
#include "sewerplan/domain/validator.h"

#include "support/ais_testbed.h"

namespace sewerplan::domain {
namespace {

class PlanFuzzTest : public ::testing::Test {
 protected:
  void SetUp() override { ais_ = testing::load_ais_testbed(); }

  // Parses `text`; if it is a plan, validates it and checks that its text reads back the same.
  void survive(const std::string& text) {
    Diagnostics diagnostics;
    Result<Plan> plan = parse_plan(text, "fuzz.plan", ais_.map, ais_.mission, diagnostics);
    if (!plan.has_value()) {
      EXPECT_EQ(plan.error().code, ErrorCode::kParse);
      EXPECT_TRUE(diagnostics.has_errors());
      return;
    }
    const ValidationReport report = validate_plan(*plan, ais_.map, ais_.mission);
    EXPECT_EQ(report.valid, report.error.empty());
    const std::string again = format_plan(*plan, ais_.map, ais_.mission);
    Diagnostics d2;
    Result<Plan> reread = parse_plan(again, "again.plan", ais_.map, ais_.mission, d2);
    ASSERT_TRUE(reread.has_value()) << reread.error() << "\nfrom:\n" << text;
    EXPECT_EQ(*reread, *plan);
  }

  testing::AisTestbed ais_;
};

TEST_F(PlanFuzzTest, SurvivesEveryTruncationOfThePapersPlan) {
  const std::string paper(testing::kPaperPlan);
  for (std::size_t n = 0; n <= paper.size(); ++n) survive(paper.substr(0, n));
}

TEST_F(PlanFuzzTest, SurvivesRandomBytes) {
  Rng rng(20040426);
  for (int round = 0; round < 500; ++round) {
    std::string text(rng.below(200), '\0');
    for (char& c : text) c = static_cast<char>(rng.below(256));
    survive(text);
  }
}

TEST_F(PlanFuzzTest, SurvivesMutationsOfThePapersPlan) {
  const std::string paper(testing::kPaperPlan);
  const std::string alphabet = " \t\n\r;#()_:-0123456789PMpmstepTYPE";
  Rng rng(7);
  for (int round = 0; round < 2000; ++round) {
    std::string text = paper;
    const auto edits = 1 + rng.below(6);
    for (std::uint64_t e = 0; e < edits && !text.empty(); ++e) {
      const auto at = static_cast<std::size_t>(rng.below(text.size()));
      switch (rng.below(4)) {
        case 0:
          text.erase(at, 1 + rng.below(8));
          break;
        case 1:
          text.insert(at, 1, alphabet[rng.below(alphabet.size())]);
          break;
        case 2:
          text[at] = static_cast<char>(rng.below(256));
          break;
        default:
          text.insert(at, text.substr(rng.below(text.size()), rng.below(30)));
          break;
      }
    }
    survive(text);
  }
}

TEST_F(PlanFuzzTest, SurvivesEveryPermutationOfOneLinesTokens) {
  std::vector<std::string> tokens = {
      "DRIVE_MANHOLE_TYPE_4_FROM_3_TO_4", "M6", "P10", "P4", "P5", "P6"};
  std::sort(tokens.begin(), tokens.end());
  do {
    std::string line;
    for (const std::string& t : tokens) line += t + " ";
    survive(line);
  } while (std::next_permutation(tokens.begin(), tokens.end()));
}

// Steps with IDs in and out of range, in random order: replaying and formatting them must fail
// cleanly, never abort.
TEST_F(PlanFuzzTest, SurvivesRandomStepsWithAnyIds) {
  Rng rng(11);
  auto id = [&rng](std::size_t count) { return static_cast<std::uint32_t>(rng.below(count + 3)); };
  const std::size_t manholes = ais_.map.manhole_count();
  const std::size_t pipes = ais_.map.pipe_count();
  const std::size_t tasks = ais_.mission.tasks.size();
  for (int round = 0; round < 300; ++round) {
    Plan plan;
    for (std::uint64_t n = rng.below(12); n > 0; --n) {
      const auto slot = [&] { return SlotIndex{static_cast<std::uint16_t>(rng.below(6))}; };
      switch (rng.below(7)) {
        case 0:
          plan.steps.push_back(DrivePipeToManhole{PipeId{id(pipes)}, ManholeId{id(manholes)}});
          break;
        case 1:
          plan.steps.push_back(DriveManhole{ManholeId{id(manholes)}, slot(), slot()});
          break;
        case 2:
          plan.steps.push_back(EnterPipe{ManholeId{id(manholes)}, PipeId{id(pipes)}});
          break;
        case 3:
          plan.steps.push_back(TakeWaterSample{PipeId{id(pipes)}, TaskId{id(tasks)}});
          break;
        case 4:
          plan.steps.push_back(InspectPipe{PipeId{id(pipes)}, TaskId{id(tasks)},
                                           static_cast<std::uint8_t>(rng.below(3))});
          break;
        case 5:
          plan.steps.push_back(GoToPoint{PipeId{id(pipes)}, TaskId{id(tasks)}});
          break;
        default:
          plan.steps.push_back(GoToManhole{ManholeId{id(manholes)}, TaskId{id(tasks)}});
          break;
      }
    }
    const ValidationReport report = validate_plan(plan, ais_.map, ais_.mission);
    EXPECT_EQ(report.valid, report.error.empty());
    EXPECT_FALSE(format_plan(plan, ais_.map, ais_.mission).empty() && !plan.steps.empty());
  }
}

}  // namespace
}  // namespace sewerplan::domain
