// SPDX-License-Identifier: MIT
// The network as SVG (svg_map.h).
#include "sewerplan/render/svg_map.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "sewerplan/core/overloaded.h"

namespace sewerplan::render {
namespace {

struct Point {
  double x = 0;
  double y = 0;
};

std::string f1(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f", v);
  return buffer;
}

std::string escape(std::string_view s) {
  std::string out;
  for (char c : s) {
    if (c == '&')
      out += "&amp;";
    else if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

constexpr double kMargin = 30;
constexpr double kTitleHeight = 36;
constexpr double kLegendHeight = 150;

// World (metres, y up) to picture (pixels, y down), to scale.
struct Box {
  double min_x = 0;
  double max_x = 1;
  double min_y = 0;
  double max_y = 1;
};

Box map_box(const SewerMap& map) {
  Box b;
  bool first = true;
  for (const Manhole& m : map.manholes()) {
    if (first) {
      b = {m.position.x_m, m.position.x_m, m.position.y_m, m.position.y_m};
      first = false;
    }
    b.min_x = std::min(b.min_x, m.position.x_m);
    b.max_x = std::max(b.max_x, m.position.x_m);
    b.min_y = std::min(b.min_y, m.position.y_m);
    b.max_y = std::max(b.max_y, m.position.y_m);
  }
  return b;
}

class Projection {
 public:
  // `box` in metres, widened by 3 % of its larger side (at least `min_margin_m`) on each side.
  Projection(Box box, double width_px, double min_margin_m = 0) {
    const double span = std::max({box.max_x - box.min_x, box.max_y - box.min_y, 1.0});
    const double margin = std::max(span * 0.03, min_margin_m);
    box.min_x -= margin;
    box.max_x += margin;
    box.min_y -= margin;
    box.max_y += margin;
    min_x_ = box.min_x;
    max_y_ = box.max_y;
    const double w = std::max(box.max_x - box.min_x, 1.0);
    const double h = std::max(box.max_y - box.min_y, 1.0);
    scale_ = (width_px - 2 * kMargin) / w;
    // Very tall networks: at most twice as high as wide.
    scale_ = std::min(scale_, 2 * (width_px - 2 * kMargin) / h);
    map_height_px_ = h * scale_;
  }
  Point operator()(double x, double y) const {
    return {kMargin + (x - min_x_) * scale_, kTitleHeight + (max_y_ - y) * scale_};
  }
  // Back to metres.
  Point world(const Point& px) const {
    return {min_x_ + (px.x - kMargin) / scale_, max_y_ - (px.y - kTitleHeight) / scale_};
  }
  double scale() const { return scale_; }
  double map_height_px() const { return map_height_px_; }

 private:
  double min_x_ = 0;
  double max_y_ = 0;
  double scale_ = 1;
  double map_height_px_ = 0;
};

class Drawing {
 public:
  Drawing(const RenderInput& in) : in_(in), map_(*in.map), p_(map_box(map_), in.width_px) {
    if (in_.focus) focus();
  }

  std::string draw() {
    const double height = kTitleHeight + p_.map_height_px() + kLegendHeight;
    out_ << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << f1(in_.width_px)
         << "\" height=\"" << f1(height) << "\" viewBox=\"0 0 " << f1(in_.width_px) << ' '
         << f1(height) << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
    out_ << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    std::string title = in_.title;
    if (title.empty()) {
      title = map_.name();
      if (in_.mission != nullptr) title += (title.empty() ? "" : ": ") + in_.mission->name;
    }
    out_ << "<text id=\"title\" x=\"" << f1(in_.width_px / 2)
         << "\" y=\"24\" text-anchor=\"middle\" font-size=\"16\">" << escape(title) << "</text>\n";
    // Everything on the map is clipped to its area (a focused picture cuts the network off).
    out_ << "<clipPath id=\"map-area\"><rect x=\"0\" y=\"" << f1(kTitleHeight) << "\" width=\""
         << f1(in_.width_px) << "\" height=\"" << f1(p_.map_height_px()) << "\"/></clipPath>\n"
         << "<g id=\"map\" clip-path=\"url(#map-area)\">\n";
    pipes();
    if (in_.mission != nullptr) tasks();
    if (in_.trace != nullptr) {
      route("driven", in_.trace->driven, "#2ca02c", 7, "", 0.55);
    }
    if (in_.plan != nullptr) route("planned", in_.plan->steps, "#1f4fd8", 2.5, "8 5", 1);
    // The start under the manholes: a mission often starts next to the exit it ends at.
    if (in_.mission != nullptr) start();
    manholes();
    if (in_.faults != nullptr) faults();
    if (in_.trace != nullptr) blocked();
    out_ << "</g>\n";
    scale_bar();
    legend();
    out_ << "</svg>\n";
    return out_.str();
  }

 private:
  // The picture around the mission: its start and tasks, the routes, the pipes found blocked.
  void focus() {
    if (in_.mission == nullptr) return;
    std::vector<Point> points{place_point(in_.mission->start)};
    for (const Task& t : in_.mission->tasks) {
      if (t.kind == TaskKind::kInspectPipe) {
        const auto ends = pipe_ends(std::get<PipeSpot>(t.place).pipe);
        points.insert(points.end(), ends.begin(), ends.end());
      } else {
        points.push_back(place_point(t.place));
      }
    }
    for (const auto* steps : {in_.plan != nullptr ? &in_.plan->steps : nullptr,
                              in_.trace != nullptr ? &in_.trace->driven : nullptr}) {
      if (steps == nullptr) continue;
      const std::vector<Point> route = route_points(*steps);
      points.insert(points.end(), route.begin(), route.end());
    }
    if (in_.trace != nullptr) {
      for (const Blockage& b : in_.trace->blocked) points.push_back(pipe_point(b.pipe, b.offset_m));
    }
    Box box;
    bool first = true;
    for (const Point& px : points) {
      const Point w = p_.world(px);
      if (first) {
        box = {w.x, w.x, w.y, w.y};
        first = false;
      }
      box.min_x = std::min(box.min_x, w.x);
      box.max_x = std::max(box.max_x, w.x);
      box.min_y = std::min(box.min_y, w.y);
      box.max_y = std::max(box.max_y, w.y);
    }
    p_ = Projection(box, in_.width_px, 10);
  }

  Point manhole_point(ManholeId m) const {
    const Position& pos = map_.manhole(m).position;
    return p_(pos.x_m, pos.y_m);
  }

  // A pipe's two drawn ends: its manholes, or for a blind end a stub along the slot's azimuth.
  std::array<Point, 2> pipe_ends(PipeId id) const {
    const Pipe& pipe = map_.pipe(id);
    std::array<std::optional<Point>, 2> ends;
    for (std::size_t e = 0; e < 2; ++e) {
      if (pipe.ends[e].manhole) ends[e] = manhole_point(*pipe.ends[e].manhole);
    }
    for (std::size_t e = 0; e < 2; ++e) {
      if (ends[e]) continue;
      const std::size_t other = 1 - e;
      if (!pipe.ends[other].manhole) {
        ends[e] = ends[other] = p_(0, 0);
        continue;
      }
      const ManholeId m = *pipe.ends[other].manhole;
      const Slot& slot = map_.slot(m, pipe.ends[other].slot);
      const double length = std::min(pipe.length_m, 30.0) * p_.scale();
      const double a = slot.azimuth_deg * 3.14159265358979323846 / 180;
      const Point from = manhole_point(m);
      ends[e] = Point{from.x + length * std::cos(a), from.y - length * std::sin(a)};
    }
    return {*ends[0], *ends[1]};
  }

  Point pipe_point(PipeId id, double offset_m) const {
    const auto [a, b] = pipe_ends(id);
    const double length = map_.pipe(id).length_m;
    const double t = length > 0 ? std::clamp(offset_m / length, 0.0, 1.0) : 0.5;
    return {a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t};
  }

  Point place_point(const Place& place) const {
    if (const auto* m = std::get_if<ManholeId>(&place)) return manhole_point(*m);
    const auto& spot = std::get<PipeSpot>(place);
    double offset = map_.pipe(spot.pipe).length_m / 2;
    if (spot.point) offset = map_.point(*spot.point).offset_m;
    if (spot.offset_m) offset = *spot.offset_m;
    return pipe_point(spot.pipe, offset);
  }

  bool drivable(const Pipe& pipe) const {
    if (in_.mission == nullptr) return true;
    const RobotProfile& r = in_.mission->profile;
    return pipe.diameter_m >= r.min_pipe_diameter_m && pipe.diameter_m <= r.max_pipe_diameter_m;
  }

  void pipes() {
    out_ << "<g id=\"pipes\" stroke-linecap=\"round\">\n";
    const bool labels = map_.pipe_count() <= 60;
    for (PipeId id : map_.pipe_ids()) {
      const Pipe& pipe = map_.pipe(id);
      const auto [a, b] = pipe_ends(id);
      const double width = std::clamp(pipe.diameter_m * 6, 0.8, 8.0);
      out_ << "<line class=\"pipe\" x1=\"" << f1(a.x) << "\" y1=\"" << f1(a.y) << "\" x2=\""
           << f1(b.x) << "\" y2=\"" << f1(b.y) << "\" stroke=\""
           << (drivable(pipe) ? "#6b8fb3" : "#c8c8c8") << "\" stroke-width=\"" << f1(width)
           << "\"><title>" << escape(pipe.name) << ", " << f1(pipe.length_m) << " m, DN "
           << std::lround(pipe.diameter_m * 1000) << "</title></line>\n";
      if (labels) {
        out_ << "<text class=\"pipe-label\" x=\"" << f1((a.x + b.x) / 2 + 4) << "\" y=\""
             << f1((a.y + b.y) / 2 - 4) << "\" font-size=\"9\" fill=\"#44617f\">"
             << escape(pipe.name) << "</text>\n";
      }
    }
    out_ << "</g>\n";
  }

  void manholes() {
    out_ << "<g id=\"manholes\">\n";
    const bool labels = map_.manhole_count() <= 60;
    const double r = map_.manhole_count() > 300 ? 1.5 : 4;
    for (ManholeId id : map_.manhole_ids()) {
      const Manhole& m = map_.manhole(id);
      const Point c = manhole_point(id);
      if (m.exit) {
        out_ << "<rect class=\"exit\" x=\"" << f1(c.x - r - 2) << "\" y=\"" << f1(c.y - r - 2)
             << "\" width=\"" << f1(2 * r + 4) << "\" height=\"" << f1(2 * r + 4)
             << "\" fill=\"#ffd400\" stroke=\"black\" stroke-width=\"1\"><title>" << escape(m.name)
             << " (exit)</title></rect>\n";
      } else {
        out_ << "<circle class=\"manhole\" cx=\"" << f1(c.x) << "\" cy=\"" << f1(c.y) << "\" r=\""
             << f1(r) << "\" fill=\"white\" stroke=\"black\" stroke-width=\"1\"><title>"
             << escape(m.name) << "</title></circle>\n";
      }
      if (labels) {
        out_ << "<text class=\"manhole-label\" x=\"" << f1(c.x + r + 3) << "\" y=\""
             << f1(c.y + r + 9) << "\">" << escape(m.name) << "</text>\n";
      }
    }
    out_ << "</g>\n";
  }

  void tasks() {
    const Mission& mission = *in_.mission;
    out_ << "<g id=\"tasks\">\n";
    for (const Task& t : mission.tasks) {
      const bool done = in_.trace != nullptr &&
                        std::find(in_.trace->tasks_done.begin(), in_.trace->tasks_done.end(),
                                  t.name) != in_.trace->tasks_done.end();
      const std::string fill = done ? "#2ca02c" : "#ff7f0e";
      const std::string tip = escape(t.name) + (done ? " (done)" : "");
      if (t.kind == TaskKind::kInspectPipe) {
        const auto& spot = std::get<PipeSpot>(t.place);
        const auto [a, b] = pipe_ends(spot.pipe);
        out_ << "<line class=\"task inspection\" x1=\"" << f1(a.x) << "\" y1=\"" << f1(a.y)
             << "\" x2=\"" << f1(b.x) << "\" y2=\"" << f1(b.y) << "\" stroke=\"" << fill
             << "\" stroke-width=\"10\" stroke-opacity=\"0.45\"><title>" << tip
             << "</title></line>\n";
        continue;
      }
      const Point c = place_point(t.place);
      if (t.kind == TaskKind::kTakeWaterSample) {
        out_ << "<path class=\"task sample\" d=\"M" << f1(c.x) << ' ' << f1(c.y - 7) << " L"
             << f1(c.x + 6) << ' ' << f1(c.y + 5) << " L" << f1(c.x - 6) << ' ' << f1(c.y + 5)
             << " Z\" fill=\"" << fill << "\" stroke=\"black\"><title>" << tip
             << "</title></path>\n";
      } else {
        out_ << "<path class=\"task goto" << (t.final ? " final" : "") << "\" d=\"M" << f1(c.x)
             << ' ' << f1(c.y - 7) << " L" << f1(c.x + 7) << ' ' << f1(c.y) << " L" << f1(c.x)
             << ' ' << f1(c.y + 7) << " L" << f1(c.x - 7) << ' ' << f1(c.y) << " Z\" fill=\""
             << fill << "\" stroke=\"black\"><title>" << tip << (t.final ? ", final" : "")
             << "</title></path>\n";
      }
    }
    out_ << "</g>\n";
  }

  // The points a sequence of steps passes, from the mission's start.
  std::vector<Point> route_points(const std::vector<domain::PlanStep>& steps) const {
    const Mission& mission = *in_.mission;
    std::vector<Point> points{place_point(mission.start)};
    // The manhole the robot is in, when in_manhole; else it is in a pipe.
    bool in_manhole = false;
    ManholeId at{0};
    if (const auto* m = std::get_if<ManholeId>(&mission.start)) {
      in_manhole = true;
      at = *m;
    }
    auto task_point = [&](TaskId t) { return place_point(mission.task(t).place); };
    for (const domain::PlanStep& step : steps) {
      std::visit(Overloaded{[&](const domain::DrivePipeToManhole& s) {
                              points.push_back(manhole_point(s.manhole));
                              in_manhole = true;
                              at = s.manhole;
                            },
                            [&](const domain::DriveManhole&) {},
                            [&](const domain::EnterPipe& s) {
                              points.push_back(manhole_point(s.manhole));
                              in_manhole = false;
                            },
                            [&](const domain::TakeWaterSample& s) {
                              points.push_back(task_point(s.task));
                              in_manhole = false;
                            },
                            [&](const domain::GoToPoint& s) {
                              points.push_back(task_point(s.task));
                              in_manhole = false;
                            },
                            [&](const domain::GoToManhole& s) {
                              points.push_back(manhole_point(s.manhole));
                              in_manhole = true;
                              at = s.manhole;
                            },
                            [&](const domain::InspectPipe& s) {
                              const Pipe& pipe = map_.pipe(s.pipe);
                              std::uint8_t end = 1;
                              if (s.finish_end) {
                                end = *s.finish_end;
                              } else if (in_manhole && pipe.ends[1].manhole.has_value() &&
                                         *pipe.ends[1].manhole == at) {
                                end = 0;
                              }
                              points.push_back(pipe_point(s.pipe, end == 0 ? 0 : pipe.length_m));
                              in_manhole = false;
                            }},
                 step);
    }
    return points;
  }

  void route(const char* id, const std::vector<domain::PlanStep>& steps, const char* colour,
             double width, const char* dash, double opacity) {
    if (in_.mission == nullptr) return;
    const std::vector<Point> points = route_points(steps);
    out_ << "<polyline id=\"" << id << "\" class=\"route\" fill=\"none\" stroke=\"" << colour
         << "\" stroke-width=\"" << f1(width) << "\" stroke-linejoin=\"round\" stroke-opacity=\""
         << f1(opacity) << "\""
         << (dash[0] != 0 ? std::string(" stroke-dasharray=\"") + dash + "\"" : "") << " points=\"";
    for (std::size_t i = 0; i < points.size(); ++i) {
      out_ << (i == 0 ? "" : " ") << f1(points[i].x) << ',' << f1(points[i].y);
    }
    out_ << "\"><title>" << id << " route, " << steps.size() << " steps</title></polyline>\n";
  }

  void cross(const Point& c, const char* cls, const char* colour, const std::string& tip) {
    out_ << "<path class=\"" << cls << "\" d=\"M" << f1(c.x - 6) << ' ' << f1(c.y - 6) << " L"
         << f1(c.x + 6) << ' ' << f1(c.y + 6) << " M" << f1(c.x - 6) << ' ' << f1(c.y + 6) << " L"
         << f1(c.x + 6) << ' ' << f1(c.y - 6) << "\" stroke=\"" << colour
         << "\" stroke-width=\"3\"><title>" << escape(tip) << "</title></path>\n";
  }

  void faults() {
    const hal::FaultScenario& f = *in_.faults;
    out_ << "<g id=\"faults\">\n";
    for (const hal::Obstacle& o : f.obstacles) {
      const Point c = pipe_point(o.pipe, o.offset_m);
      out_ << "<rect class=\"fault obstacle\" x=\"" << f1(c.x - 3.5) << "\" y=\"" << f1(c.y - 3.5)
           << "\" width=\"7\" height=\"7\" fill=\""
           << (o.kind == hal::ObstacleKind::kPermanent ? "black" : "#999999")
           << "\"><title>obstacle in " << escape(map_.pipe(o.pipe).name) << " at " << f1(o.offset_m)
           << " m (" << hal::to_string(o.kind) << ")</title></rect>\n";
    }
    for (const hal::DangerSpot& d : f.danger_spots) {
      const Point c = pipe_point(d.pipe, d.offset_m);
      out_ << "<circle class=\"fault danger\" cx=\"" << f1(c.x) << "\" cy=\"" << f1(c.y)
           << "\" r=\"4\" fill=\"#9467bd\"><title>danger in " << escape(map_.pipe(d.pipe).name)
           << " at " << f1(d.offset_m) << " m</title></circle>\n";
    }
    for (const hal::DangerousPassage& p : f.dangerous_passages) {
      const Point c = manhole_point(p.manhole);
      out_ << "<circle class=\"fault passage\" cx=\"" << f1(c.x) << "\" cy=\"" << f1(c.y)
           << "\" r=\"9\" fill=\"none\" stroke=\"#9467bd\" stroke-width=\"2\"><title>dangerous "
              "passage in "
           << escape(map_.manhole(p.manhole).name) << "</title></circle>\n";
    }
    out_ << "</g>\n";
  }

  void blocked() {
    out_ << "<g id=\"blocked\">\n";
    for (const Blockage& b : in_.trace->blocked) {
      cross(pipe_point(b.pipe, b.offset_m), "blocked", "#d62728",
            "found blocked: " + map_.pipe(b.pipe).name + " at " + f1(b.offset_m) + " m");
    }
    for (const ClosedPassage& c : in_.trace->closed) {
      const Point m = manhole_point(c.manhole);
      out_ << "<circle class=\"closed\" cx=\"" << f1(m.x) << "\" cy=\"" << f1(m.y)
           << "\" r=\"11\" fill=\"none\" stroke=\"#d62728\" stroke-width=\"3\"><title>passage "
              "closed in "
           << escape(map_.manhole(c.manhole).name) << "</title></circle>\n";
    }
    out_ << "</g>\n";
  }

  void start() {
    const Point c = place_point(in_.mission->start);
    out_ << "<g id=\"start\"><circle cx=\"" << f1(c.x) << "\" cy=\"" << f1(c.y)
         << "\" r=\"8\" fill=\"#1f4fd8\"/><text x=\"" << f1(c.x) << "\" y=\"" << f1(c.y + 4)
         << "\" text-anchor=\"middle\" fill=\"white\" font-weight=\"bold\">S</text></g>\n";
  }

  void scale_bar() {
    const double target_m = (in_.width_px - 2 * kMargin) / 5 / p_.scale();
    double length = std::pow(10.0, std::floor(std::log10(std::max(target_m, 1e-3))));
    for (double k : {2.0, 5.0, 10.0}) {
      if (length * k <= target_m) length = std::pow(10.0, std::floor(std::log10(target_m))) * k;
    }
    const double px = length * p_.scale();
    const double x = in_.width_px - kMargin - px;
    const double y = kTitleHeight + p_.map_height_px() + 18;
    out_ << "<g id=\"scale\"><line x1=\"" << f1(x) << "\" y1=\"" << f1(y) << "\" x2=\""
         << f1(x + px) << "\" y2=\"" << f1(y) << "\" stroke=\"black\" stroke-width=\"3\"/>"
         << "<text x=\"" << f1(x + px / 2) << "\" y=\"" << f1(y - 5) << "\" text-anchor=\"middle\">"
         << (length >= 1 ? std::to_string(std::lround(length)) : f1(length)) << " m</text></g>\n";
  }

  void legend() {
    double y = kTitleHeight + p_.map_height_px() + 20;
    const double x = kMargin;
    out_ << "<g id=\"legend\">\n";
    int column = 0;
    auto key = [&](const std::string& symbol, const std::string& text) {
      const double kx = x + column * 250;
      out_ << "<g transform=\"translate(" << f1(kx) << ',' << f1(y) << ")\">" << symbol
           << "<text x=\"34\" y=\"4\">" << escape(text) << "</text></g>\n";
      if (++column == 3) {
        column = 0;
        y += 20;
      }
    };
    key("<line x1=\"0\" y1=\"0\" x2=\"28\" y2=\"0\" stroke=\"#6b8fb3\" stroke-width=\"3\"/>",
        "pipe (width by diameter)");
    key("<line x1=\"0\" y1=\"0\" x2=\"28\" y2=\"0\" stroke=\"#c8c8c8\" stroke-width=\"3\"/>",
        "pipe the robot cannot drive");
    key("<circle cx=\"14\" cy=\"0\" r=\"4\" fill=\"white\" stroke=\"black\"/>", "manhole");
    key("<rect x=\"8\" y=\"-6\" width=\"12\" height=\"12\" fill=\"#ffd400\" stroke=\"black\"/>",
        "exit");
    if (in_.mission != nullptr) {
      key("<circle cx=\"14\" cy=\"0\" r=\"7\" fill=\"#1f4fd8\"/>", "start");
      key("<line x1=\"0\" y1=\"0\" x2=\"28\" y2=\"0\" stroke=\"#ff7f0e\" stroke-width=\"8\" "
          "stroke-opacity=\"0.45\"/>",
          "inspection (green: done)");
      key("<path d=\"M14 -7 L20 5 L8 5 Z\" fill=\"#ff7f0e\" stroke=\"black\"/>",
          "water sample (green: done)");
      key("<path d=\"M14 -7 L21 0 L14 7 L7 0 Z\" fill=\"#ff7f0e\" stroke=\"black\"/>",
          "go-to task or end point");
    }
    if (in_.plan != nullptr) {
      key("<line x1=\"0\" y1=\"0\" x2=\"28\" y2=\"0\" stroke=\"#1f4fd8\" stroke-width=\"2.5\" "
          "stroke-dasharray=\"8 5\"/>",
          "planned route");
    }
    if (in_.trace != nullptr) {
      key("<line x1=\"0\" y1=\"0\" x2=\"28\" y2=\"0\" stroke=\"#2ca02c\" stroke-width=\"7\" "
          "stroke-opacity=\"0.55\"/>",
          "route driven");
      key("<path d=\"M8 -6 L20 6 M8 6 L20 -6\" stroke=\"#d62728\" stroke-width=\"3\"/>",
          "found blocked / dangerous");
    }
    if (in_.faults != nullptr) {
      key("<rect x=\"10\" y=\"-4\" width=\"7\" height=\"7\" fill=\"black\"/>",
          "hidden obstacle (grey: transient)");
      key("<circle cx=\"14\" cy=\"0\" r=\"4\" fill=\"#9467bd\"/>", "hidden danger spot");
    }
    if (column != 0) y += 20;
    if (in_.trace != nullptr && !in_.trace->outcome.empty()) {
      out_ << "<text id=\"outcome\" x=\"" << f1(x) << "\" y=\"" << f1(y + 6) << "\">"
           << escape(in_.trace->outcome +
                     "; tasks done: " + std::to_string(in_.trace->tasks_done.size()) +
                     ", replans: " + std::to_string(in_.trace->replans))
           << "</text>\n";
    }
    out_ << "</g>\n";
  }

  const RenderInput& in_;
  const SewerMap& map_;
  Projection p_;
  std::ostringstream out_;
};

}  // namespace

std::string render_map_svg(const RenderInput& input) { return Drawing(input).draw(); }

}  // namespace sewerplan::render
