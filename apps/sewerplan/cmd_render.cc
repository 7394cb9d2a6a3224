// SPDX-License-Identifier: MIT
// sewerplan render --map MAP [--mission MISSION] [--plan PLAN] [--log EVENTS] [--faults FAULTS]
//                  [--profile P] [--title T] [--width PX] [--focus] -o FILE.svg|FILE.png
#include <ostream>
#include <string_view>

#include <CLI/CLI.hpp>

#include "sewerplan/core/map_io.h"
#include "sewerplan/core/mission.h"
#include "sewerplan/core/text_file.h"
#include "sewerplan/domain/plan_text.h"
#include "sewerplan/hal/fault_scenario.h"
#include "sewerplan/modules/png.h"
#include "sewerplan/render/map_picture.h"

#include "command.h"
#include "driveability_option.h"
#include "json_output.h"
#include "map_input.h"
#include "output_format.h"

namespace sewerplan::cli {
namespace {

struct RenderOptions {
  std::string map;
  std::string gis_fields;  // --gis-fields
  std::string mission;
  std::string plan;
  std::string log;
  std::string faults;
  std::string profile;
  std::string title;
  double width_px = 1000;
  bool focus = false;
  std::string out;
  bool json = false;
};

// What render writes, by -o's extension (output_format.h): SVG, the default, or PNG through cairo.
constexpr OutputExtension kPictureFormats[] = {{".svg", "svg"}, {".png", "png"}};

int run(const RenderOptions& o, Context& c) {
  const Result<std::string_view> format = output_format(o.out, "render -o", kPictureFormats);
  if (!format.has_value()) return fail(c, o.json, format.error());
  if ((!o.plan.empty() || !o.log.empty() || o.focus) && o.mission.empty()) {
    return usage_error(c, o.json, "render: --plan, --log and --focus need --mission");
  }
  if (!(o.width_px >= 200 && o.width_px <= 20000)) {
    return usage_error(c, o.json, "render: --width must be 200 to 20000 pixels");
  }
  Diagnostics diagnostics;
  auto failed = [&](const Error& e) { return fail(c, o.json, e, diagnostics); };
  Result<SewerMap> map = read_input_map({o.map, o.gis_fields}, diagnostics);
  if (!map.has_value()) return failed(map.error());
  std::optional<Mission> mission;
  if (!o.mission.empty()) {
    Result<Mission> m = read_mission(o.mission, *map, diagnostics);
    if (!m.has_value()) return failed(m.error());
    mission = std::move(*m);
  }
  std::optional<domain::Plan> plan;
  if (!o.plan.empty()) {
    Result<std::string> text = read_text_file(o.plan);
    if (!text.has_value()) return failed(text.error());
    Result<domain::Plan> p = domain::parse_plan(*text, o.plan, *map, *mission, diagnostics);
    if (!p.has_value()) return failed(p.error());
    plan = std::move(*p);
  }
  std::optional<render::EventTrace> trace;
  if (!o.log.empty()) {
    Result<render::EventTrace> t =
        render::read_event_trace_file(o.log, *map, *mission, diagnostics);
    if (!t.has_value()) return failed(t.error());
    trace = std::move(*t);
  }
  std::optional<hal::FaultScenario> faults;
  if (!o.faults.empty()) {
    Result<hal::FaultScenario> f = hal::read_faults(o.faults, *map, diagnostics);
    if (!f.has_value()) return failed(f.error());
    faults = std::move(*f);
  }
  Result<std::optional<domain::DriveabilityReport>> driveability =
      driveability_for_profile(*map, o.profile);
  if (!driveability.has_value()) return failed(driveability.error());
  print_diagnostics(diagnostics, c.err);
  const bool png = *format == "png";
  const render::RenderInput input{.map = &*map,
                                  .mission = mission ? &*mission : nullptr,
                                  .plan = plan ? &*plan : nullptr,
                                  .trace = trace ? &*trace : nullptr,
                                  .faults = faults ? &*faults : nullptr,
                                  .driveability = *driveability ? &**driveability : nullptr,
                                  .title = o.title,
                                  .width_px = o.width_px,
                                  .focus = o.focus};
  Result<std::string> picture =
      png ? modules::render_map_png(input) : Result<std::string>(render::render_map_svg(input));
  if (!picture.has_value()) return failed(picture.error());
  if (Result<void> w = write_text_file(o.out, *picture); !w.has_value()) return failed(w.error());
  if (o.json) {
    print_json(c.out, {{"wrote", o.out},
                       {"format", *format},
                       {"bytes", picture->size()},
                       {"width_px", o.width_px},
                       {"focus", o.focus},
                       {"mission", o.mission.empty() ? Json() : Json(o.mission)},
                       {"plan", o.plan.empty() ? Json() : Json(o.plan)},
                       {"log", o.log.empty() ? Json() : Json(o.log)},
                       {"faults", o.faults.empty() ? Json() : Json(o.faults)},
                       {"profile", o.profile.empty() ? Json() : Json(o.profile)}});
  } else {
    c.out << "wrote " << o.out << '\n';
  }
  return kExitOk;
}

}  // namespace

void add_render_command(CLI::App& app, Context& context) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand(
      "render",
      "Draw the network to scale as SVG or PNG, with a mission, a plan, faults, a driven route "
      "and what a robot can drive");
  cmd->add_option("--map", options->map, "Map file")->required();
  add_gis_fields_option(*cmd, options->gis_fields);
  cmd->add_option("--mission", options->mission, "Mission file (.json): start and tasks");
  cmd->add_option("--plan", options->plan, "Plan text: the planned route");
  cmd->add_option("--log", options->log,
                  "Event log (simulate --log): route driven, blocked pipes, tasks done");
  cmd->add_option("--faults", options->faults, "Fault scenario: the hidden faults");
  cmd->add_option("--profile", options->profile,
                  "Colour the pipes by what this robot can drive from the map's exits (the "
                  "reasons of info --profile): a built-in profile or a profile JSON file");
  cmd->add_option("--title", options->title, "Title (default: map and mission names)");
  cmd->add_option("--width", options->width_px, "Width in pixels")->capture_default_str();
  cmd->add_flag("--focus", options->focus,
                "Only the mission's area (start, tasks, routes), not the whole network");
  cmd->add_option("-o,--out", options->out, "File to write: .svg or .png (no extension: SVG)")
      ->required();
  cmd->add_flag("--json", options->json, "Print what was written as JSON");
  cmd->callback([options, &context] { context.exit_code = run(*options, context); });
}

}  // namespace sewerplan::cli
