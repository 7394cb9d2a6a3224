// SPDX-License-Identifier: MIT
#include <algorithm>
#include <string>

#include <gtest/gtest.h>
#include <pugixml.hpp>

#include "sewerplan/core/generator.h"
#include "sewerplan/core/text_file.h"
#include "sewerplan/domain/mission_generator.h"
#include "sewerplan/domain/plan_text.h"
#include "sewerplan/render/svg_map.h"

#include "support/ais_testbed.h"

namespace sewerplan::render {
namespace {

// A log as `simulate --log` writes it (other event types and fields are skipped).
constexpr std::string_view kLog =
    R"log({"t_s":0,"type":"plan","reason":"start","goals":["sample","inspect","end"]}
{"t_s":0,"type":"action","step":"DRIVE_PIPE_TO_MANHOLE P12 M2","kind":"drive_to_manhole"}
{"t_s":10,"type":"job","job":"DriveForward(0.30 m/s, 2.00 m)","progress_m":2,"ok":true}
{"t_s":10,"type":"action","step":"DRIVE_MANHOLE_TYPE_2_FROM_1_TO_2 M2 P12 P1"}
{"t_s":20,"type":"action","step":"DRIVE_PIPE_TO_MANHOLE P1 M3"}
{"t_s":30,"type":"failure","kind":"blockage","pipe":"P1","offset_m":4.5,"detail":"obstacle"}
{"t_s":30,"type":"failure","kind":"dangerous passage","manhole":"M6","from_slot":3,"to_slot":4}
{"t_s":30,"type":"replan","reason":"blockage in P1 at 4.50 m"}
{"t_s":31,"type":"task_done","task":"sample"}
{"t_s":90,"type":"mission_end","outcome":"ended","end":"exit M1","tasks_done":["sample"]}
)log";

struct Picture {
  pugi::xml_document doc;
  std::string text;
};

std::size_t count(const pugi::xml_document& doc, const char* xpath) {
  return doc.select_nodes(xpath).size();
}

TEST(Render, TheNetworkPlanAndLogAreDrawnWithALegend) {
  const auto ais = testing::load_ais_testbed();
  Result<std::string> plan_text = read_text_file(
      std::string(SEWERPLAN_SOURCE_DIR) + "/datasets/ais-testbed/plans/paper-corrected.plan");
  ASSERT_TRUE(plan_text.has_value());
  Diagnostics diagnostics;
  Result<domain::Plan> plan =
      domain::parse_plan(*plan_text, "paper-corrected.plan", ais.map, ais.mission, diagnostics);
  ASSERT_TRUE(plan.has_value());
  Result<EventTrace> trace =
      read_event_trace(kLog, "events.jsonl", ais.map, ais.mission, diagnostics);
  ASSERT_TRUE(trace.has_value()) << trace.error().message;
  EXPECT_EQ(trace->driven.size(), 3U);
  ASSERT_EQ(trace->blocked.size(), 1U);
  EXPECT_EQ(trace->blocked[0].offset_m, 4.5);
  ASSERT_EQ(trace->closed.size(), 1U);
  EXPECT_EQ(trace->closed[0].from, SlotIndex{2});
  EXPECT_EQ(trace->outcome, "ended at exit M1");

  const RenderInput input{
      .map = &ais.map, .mission = &ais.mission, .plan = &*plan, .trace = &*trace};
  Picture p;
  p.text = render_map_svg(input);
  const pugi::xml_parse_result parsed = p.doc.load_string(p.text.c_str());
  ASSERT_TRUE(parsed) << parsed.description() << "\n" << p.text;
  EXPECT_EQ(count(p.doc, "//g[@id='pipes']/line[@class='pipe']"), ais.map.pipe_count());
  std::size_t exits = 0;
  for (const Manhole& m : ais.map.manholes()) exits += m.exit ? 1 : 0;
  EXPECT_EQ(count(p.doc, "//g[@id='manholes']/rect[@class='exit']"), exits);
  EXPECT_EQ(count(p.doc, "//g[@id='manholes']/circle[@class='manhole']"),
            ais.map.manhole_count() - exits);
  EXPECT_EQ(count(p.doc, "//g[@id='tasks']/*"), ais.mission.tasks.size());
  EXPECT_EQ(count(p.doc, "//g[@id='tasks']/path[@class='task sample']"), 1U);
  // The sample was done: drawn green.
  EXPECT_STREQ(p.doc.select_node("//path[@class='task sample']").node().attribute("fill").value(),
               "#2ca02c");
  const pugi::xml_node planned = p.doc.select_node("//polyline[@id='planned']").node();
  ASSERT_TRUE(planned);
  const std::string points = planned.attribute("points").value();
  // A point for the start and for every step but a pass through a manhole (it stays there).
  const auto passes = std::count_if(plan->steps.begin(), plan->steps.end(), [](const auto& s) {
    return std::holds_alternative<domain::DriveManhole>(s);
  });
  EXPECT_EQ(std::count(points.begin(), points.end(), ','),
            static_cast<std::ptrdiff_t>(plan->steps.size()) - passes + 1);
  EXPECT_TRUE(p.doc.select_node("//polyline[@id='driven']"));
  EXPECT_EQ(count(p.doc, "//g[@id='blocked']/path[@class='blocked']"), 1U);
  EXPECT_EQ(count(p.doc, "//g[@id='blocked']/circle[@class='closed']"), 1U);
  EXPECT_TRUE(p.doc.select_node("//g[@id='scale']"));
  EXPECT_TRUE(p.doc.select_node("//g[@id='start']"));
  EXPECT_GE(count(p.doc, "//g[@id='legend']/g"), 10U);
  EXPECT_NE(std::string(p.doc.select_node("//text[@id='title']").node().child_value())
                .find(ais.mission.name),
            std::string::npos);
  EXPECT_NE(p.text.find("ended at exit M1; tasks done: 1, replans: 1"), std::string::npos);
  // Deterministic.
  EXPECT_EQ(render_map_svg(input), p.text);
}

TEST(Render, TheMapAloneAndHiddenFaults) {
  const auto ais = testing::load_ais_testbed();
  hal::FaultScenario faults;
  faults.obstacles.push_back({*ais.map.find_pipe("P4"), 1.0, hal::ObstacleKind::kPermanent});
  faults.danger_spots.push_back({*ais.map.find_pipe("P5"), 2.0});
  const std::string text = render_map_svg({.map = &ais.map, .faults = &faults, .title = "A & B"});
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_string(text.c_str()));
  EXPECT_EQ(count(doc, "//g[@id='faults']/rect[@class='fault obstacle']"), 1U);
  EXPECT_EQ(count(doc, "//g[@id='faults']/circle[@class='fault danger']"), 1U);
  EXPECT_FALSE(doc.select_node("//g[@id='tasks']"));
  EXPECT_FALSE(doc.select_node("//polyline"));
  EXPECT_STREQ(doc.select_node("//text[@id='title']").node().child_value(), "A & B");
}

// Focused on a mission in a large network: the picture's scale follows the mission's area.
TEST(Render, FocusShowsTheMissionsArea) {
  Result<SewerMap> map = generate_network({.manholes = 400, .seed = 3});
  ASSERT_TRUE(map.has_value());
  Result<Mission> mission = domain::generate_mission(*map, {.tasks = 3, .seed = 3});
  ASSERT_TRUE(mission.has_value());
  const std::string whole = render_map_svg({.map = &*map, .mission = &*mission});
  const std::string focused = render_map_svg({.map = &*map, .mission = &*mission, .focus = true});
  pugi::xml_document a;
  pugi::xml_document b;
  ASSERT_TRUE(a.load_string(whole.c_str()));
  ASSERT_TRUE(b.load_string(focused.c_str()));
  // The scale bar stands for fewer metres in the focused picture.
  auto metres = [](const pugi::xml_document& doc) {
    return std::stod(doc.select_node("//g[@id='scale']/text").node().child_value());
  };
  EXPECT_LT(metres(b), metres(a));
  EXPECT_TRUE(b.select_node("//clipPath[@id='map-area']"));
  EXPECT_EQ(count(b, "//g[@id='map']/g[@id='pipes']/line"), map->pipe_count());
}

TEST(Render, ABadEventLogNamesFileAndLine) {
  const auto ais = testing::load_ais_testbed();
  const std::string bad =
      "{\"type\":\"plan\"}\nnot json\n{\"type\":\"action\",\"step\":\"FLY P1\"}\n"
      "{\"type\":\"failure\",\"pipe\":\"P99\",\"offset_m\":1}\n";
  Diagnostics diagnostics;
  Result<EventTrace> trace = read_event_trace(bad, "ev.jsonl", ais.map, ais.mission, diagnostics);
  ASSERT_FALSE(trace.has_value());
  ASSERT_EQ(diagnostics.error_count(), 3U);
  std::ostringstream all;
  for (const Diagnostic& d : diagnostics.all()) all << d << '\n';
  EXPECT_NE(all.str().find("ev.jsonl:2"), std::string::npos) << all.str();
  EXPECT_NE(all.str().find("ev.jsonl:3"), std::string::npos) << all.str();
  EXPECT_NE(all.str().find("ev.jsonl:4"), std::string::npos) << all.str();
}

}  // namespace
}  // namespace sewerplan::render
