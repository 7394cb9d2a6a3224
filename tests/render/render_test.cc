// SPDX-License-Identifier: MIT
#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>

#include <gtest/gtest.h>
#include <pugixml.hpp>

#include "sewerplan/core/generator.h"
#include "sewerplan/core/text_file.h"
#include "sewerplan/domain/driveability.h"
#include "sewerplan/domain/mission_generator.h"
#include "sewerplan/domain/plan_text.h"
#include "sewerplan/modules/png.h"
#include "sewerplan/render/map_picture.h"

#include "support/ais_testbed.h"
#include "support/paths.h"
#include <cairo.h>

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
  Result<std::string> plan_text =
      read_text_file(sewerplan::testing::dataset_path("ais-testbed/plans/paper-corrected.plan"));
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

// A PNG decoded by cairo (not by the code that wrote it: its own reader, libpng underneath).
struct Decoded {
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface{
      nullptr, &cairo_surface_destroy};
  int width() const { return cairo_image_surface_get_width(surface.get()); }
  int height() const { return cairo_image_surface_get_height(surface.get()); }
  // 0xRRGGBB of the pixel at (x, y).
  std::uint32_t pixel(int x, int y) const {
    const unsigned char* row =
        cairo_image_surface_get_data(surface.get()) +
        static_cast<std::ptrdiff_t>(y) * cairo_image_surface_get_stride(surface.get());
    std::uint32_t argb = 0;
    std::memcpy(&argb, row + 4 * x, 4);
    return argb & 0xffffffU;
  }
};

Decoded decode_png(const std::string& bytes) {
  struct Reader {
    const std::string* bytes;
    std::size_t at = 0;
  } reader{&bytes};
  Decoded d;
  d.surface.reset(cairo_image_surface_create_from_png_stream(
      [](void* closure, unsigned char* data, unsigned int length) {
        auto* r = static_cast<Reader*>(closure);
        if (r->at + length > r->bytes->size()) return CAIRO_STATUS_READ_ERROR;
        std::memcpy(data, r->bytes->data() + r->at, length);
        r->at += length;
        return CAIRO_STATUS_SUCCESS;
      },
      &reader));
  cairo_surface_flush(d.surface.get());
  return d;
}

bool near(std::uint32_t rgb, std::uint32_t want, int tolerance) {
  for (int shift : {0, 8, 16}) {
    const int a = static_cast<int>((rgb >> shift) & 0xff);
    const int b = static_cast<int>((want >> shift) & 0xff);
    if (std::abs(a - b) > tolerance) return false;
  }
  return true;
}

// The PNG is the SVG's scene: the same size, and a pipe's colour where the SVG draws the pipe.
TEST(Render, APngDecodesWithThePipesWhereTheSvgDrawsThem) {
  const auto ais = testing::load_ais_testbed();
  const RenderInput input{.map = &ais.map, .width_px = 800};
  Result<std::string> png = modules::render_map_png(input);
  ASSERT_TRUE(png.has_value()) << png.error().message;
  ASSERT_GT(png->size(), 8U);
  EXPECT_EQ(png->substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  const Decoded d = decode_png(*png);
  ASSERT_EQ(cairo_surface_status(d.surface.get()), CAIRO_STATUS_SUCCESS);
  pugi::xml_document svg;
  ASSERT_TRUE(svg.load_string(render_map_svg(input).c_str()));
  EXPECT_EQ(d.width(), 800);
  EXPECT_EQ(d.height(),
            static_cast<int>(std::ceil(svg.child("svg").attribute("height").as_double())));
  EXPECT_EQ(d.pixel(2, 2), 0xffffffU);  // the white background
  // The middle of the longest pipe is drawn in the pipe's colour (#6b8fb3).
  pugi::xml_node longest;
  double length = 0;
  for (const pugi::xpath_node& n : svg.select_nodes("//g[@id='pipes']/line[@class='pipe']")) {
    const pugi::xml_node l = n.node();
    const double dx = l.attribute("x2").as_double() - l.attribute("x1").as_double();
    const double dy = l.attribute("y2").as_double() - l.attribute("y1").as_double();
    if (std::hypot(dx, dy) > length) {
      length = std::hypot(dx, dy);
      longest = l;
    }
  }
  ASSERT_TRUE(longest);
  EXPECT_STREQ(longest.attribute("stroke").value(), "#6b8fb3");
  const double mx = (longest.attribute("x1").as_double() + longest.attribute("x2").as_double()) / 2;
  const double my = (longest.attribute("y1").as_double() + longest.attribute("y2").as_double()) / 2;
  const std::uint32_t at = d.pixel(static_cast<int>(mx), static_cast<int>(my));
  EXPECT_TRUE(near(at, 0x6b8fb3, 40)) << std::hex << at;
}

TEST(Render, APngTooLargeIsAnError) {
  const auto ais = testing::load_ais_testbed();
  // A very tall map at the widest width: more pixels than a PNG takes.
  Result<std::string> png = modules::render_map_png({.map = &ais.map, .width_px = 20000});
  ASSERT_FALSE(png.has_value());
  EXPECT_EQ(png.error().code, ErrorCode::kInvalidArgument);
}

// A network of 5,000 manholes is thinned, but every element of the mission stays.
TEST(Render, LevelOfDetailThinsTheNetworkAndKeepsEveryMissionElement) {
  Result<SewerMap> map = generate_network({.manholes = 5000, .seed = 5});
  ASSERT_TRUE(map.has_value());
  ASSERT_GT(map->pipe_count(), kFullDetailPipes);
  Result<Mission> mission =
      domain::generate_mission(*map, {.tasks = 6, .seed = 5, .radius_pipes = 5000});
  ASSERT_TRUE(mission.has_value());
  hal::FaultScenario faults;
  const PipeId far_pipe{static_cast<std::uint32_t>(map->pipe_count() - 1)};
  faults.obstacles.push_back({far_pipe, 0.5, hal::ObstacleKind::kPermanent});
  const std::string text =
      render_map_svg({.map = &*map, .mission = &*mission, .faults = &faults, .width_px = 600});
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_string(text.c_str()));
  const std::size_t pipes = count(doc, "//g[@id='pipes']/line[@class='pipe']");
  const std::size_t manholes =
      count(doc, "//g[@id='manholes']/*[@class='manhole' or @class='exit']");
  EXPECT_LT(pipes, map->pipe_count());
  EXPECT_LT(manholes, map->manhole_count());
  EXPECT_EQ(count(doc, "//g[@id='tasks']/*"), mission->tasks.size());
  EXPECT_TRUE(doc.select_node("//g[@id='start']"));
  EXPECT_EQ(count(doc, "//g[@id='faults']/rect"), 1U);
  // The pipes and manholes the mission names are drawn, by their tooltips.
  auto drawn = [&](const std::string& group, const std::string& name) {
    for (const pugi::xpath_node& n : doc.select_nodes(("//g[@id='" + group + "']/*").c_str())) {
      const std::string title = n.node().child_value("title");
      if (title == name || title.starts_with(name + ",") || title.starts_with(name + " (")) {
        return true;
      }
    }
    return false;
  };
  EXPECT_TRUE(drawn("pipes", map->pipe(far_pipe).name));
  for (const Task& t : mission->tasks) {
    if (const auto* m = std::get_if<ManholeId>(&t.place)) {
      EXPECT_TRUE(drawn("manholes", map->manhole(*m).name)) << t.name;
    } else {
      const Pipe& pipe = map->pipe(std::get<PipeSpot>(t.place).pipe);
      EXPECT_TRUE(drawn("pipes", pipe.name)) << t.name;
      for (const PipeEnd& e : pipe.ends) {
        if (e.manhole) {
          EXPECT_TRUE(drawn("manholes", map->manhole(*e.manhole).name)) << t.name;
        }
      }
    }
  }
  // Names where they fit: never two overlapping, and fewer than the manholes drawn.
  EXPECT_LT(count(doc, "//text[@class='manhole-label']"), manholes);
}

// --profile: pipes coloured by why the robot cannot drive them, as info --profile reports.
TEST(Render, DriveabilityColoursThePipesByWhyNot) {
  Result<SewerMap> map = generate_network({.manholes = 200, .seed = 2});
  ASSERT_TRUE(map.has_value());
  const RobotProfile profile = *builtin_profile("makro-plus");
  const domain::DriveabilityReport report =
      domain::analyse_driveability(*map, profile, domain::default_starts(*map));
  ASSERT_FALSE(report.too_narrow.empty() && report.too_wide.empty());
  ASSERT_FALSE(report.reachable_pipes.empty());
  const std::string text = render_map_svg({.map = &*map, .driveability = &report});
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_string(text.c_str()));
  for (PipeId id : map->pipe_ids()) {
    const std::string name = map->pipe(id).name;
    const pugi::xml_node line =
        doc.select_node(("//g[@id='pipes']/line[starts-with(title, '" + name + ",')]").c_str())
            .node();
    ASSERT_TRUE(line) << name;
    const std::string_view why = domain::why_not_driveable(id, report);
    const std::string title = line.child_value("title");
    EXPECT_EQ(title.ends_with(std::string(", ") + std::string(why)), !why.empty()) << title;
    EXPECT_EQ(std::string(line.attribute("stroke").value()) == "#6b8fb3", why.empty()) << title;
  }
}

}  // namespace
}  // namespace sewerplan::render
