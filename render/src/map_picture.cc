// SPDX-License-Identifier: MIT
// The map picture as one scene drawn on a Canvas (map_picture.h).
#include "sewerplan/render/map_picture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <unordered_set>
#include <vector>

#include "sewerplan/core/overloaded.h"
#include "sewerplan/domain/route_geometry.h"

#include "svg_canvas.h"

namespace sewerplan::render {
namespace {

using domain::MapXY;

std::string f1(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f", v);
  return buffer;
}

constexpr double kMargin = 30;
constexpr double kTitleHeight = 36;
constexpr double kLegendHeight = 150;
constexpr Colour kBlack = Colour::rgb(0x000000);
constexpr Colour kWhite = Colour::rgb(0xffffff);
constexpr Colour kPipeColour = Colour::rgb(0x6b8fb3);
constexpr Colour kUndrivable = Colour::rgb(0xc8c8c8);
constexpr Colour kTooNarrow = Colour::rgb(0xe377c2);
constexpr Colour kTooWide = Colour::rgb(0x8c564b);
constexpr Colour kCutOff = Colour::rgb(0xbcbd22);
constexpr Colour kPassage = Colour::rgb(0x17becf);
constexpr Colour kExit = Colour::rgb(0xffd400);
constexpr Colour kPlanned = Colour::rgb(0x1f4fd8);
constexpr Colour kDriven = Colour::rgb(0x2ca02c);
constexpr Colour kTodo = Colour::rgb(0xff7f0e);
constexpr Colour kBlocked = Colour::rgb(0xd62728);
constexpr Colour kDanger = Colour::rgb(0x9467bd);

// A rectangle of the map in metres.
struct Box {
  double min_x = 0;
  double max_x = 1;
  double min_y = 0;
  double max_y = 1;
  bool contains(MapXY p) const {
    return p.x >= min_x && p.x <= max_x && p.y >= min_y && p.y <= max_y;
  }
};

template <typename Points>
Box box_around(const Points& points) {
  Box b;
  bool first = true;
  for (const MapXY& p : points) {
    if (first) {
      b = {p.x, p.x, p.y, p.y};
      first = false;
    }
    b.min_x = std::min(b.min_x, p.x);
    b.max_x = std::max(b.max_x, p.x);
    b.min_y = std::min(b.min_y, p.y);
    b.max_y = std::max(b.max_y, p.y);
  }
  return b;
}

Box map_box(const SewerMap& map) {
  std::vector<MapXY> points;
  points.reserve(map.manhole_count());
  for (ManholeId id : map.manhole_ids()) points.push_back(domain::manhole_point(map, id));
  return box_around(points);
}

// World (metres, y up) to picture (pixels, y down), to scale.
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
  Point operator()(MapXY p) const {
    return {kMargin + (p.x - min_x_) * scale_, kTitleHeight + (max_y_ - p.y) * scale_};
  }
  double scale() const { return scale_; }
  double map_height_px() const { return map_height_px_; }

 private:
  double min_x_ = 0;
  double max_y_ = 0;
  double scale_ = 1;
  double map_height_px_ = 0;
};

// Which cells of the picture are taken, to place names where they fit and thin manholes.
class Grid {
 public:
  Grid(double width, double height, double cell)
      : cell_(cell),
        columns_(static_cast<std::size_t>(std::max(1.0, std::ceil(width / cell)))),
        rows_(static_cast<std::size_t>(std::max(1.0, std::ceil(height / cell)))),
        taken_(columns_ * rows_, false) {}
  bool free(const Rect& r) const {
    bool all_free = true;
    visit(r, [&](std::size_t i) { all_free = all_free && !taken_[i]; });
    return all_free;
  }
  void take(const Rect& r) {
    visit(r, [&](std::size_t i) { taken_[i] = true; });
  }

 private:
  template <typename F>
  void visit(const Rect& r, F f) const {
    const auto clamp = [](double v, std::size_t n) {
      return static_cast<std::size_t>(std::clamp(v, 0.0, static_cast<double>(n - 1)));
    };
    const std::size_t x0 = clamp(std::floor(r.x / cell_), columns_);
    const std::size_t x1 = clamp(std::floor((r.x + r.width) / cell_), columns_);
    const std::size_t y0 = clamp(std::floor(r.y / cell_), rows_);
    const std::size_t y1 = clamp(std::floor((r.y + r.height) / cell_), rows_);
    for (std::size_t y = y0; y <= y1; ++y) {
      for (std::size_t x = x0; x <= x1; ++x) f(y * columns_ + x);
    }
  }
  double cell_;
  std::size_t columns_;
  std::size_t rows_;
  std::vector<bool> taken_;
};

// About how wide a name is at this font size.
double text_width(std::string_view s, double size) {
  return 0.6 * size * static_cast<double>(s.size());
}

class Scene {
 public:
  Scene(const RenderInput& in, Canvas& canvas)
      : in_(in), map_(*in.map), c_(canvas), p_(map_box(map_), in.width_px) {
    tags_ = c_.keeps_tags();
    mark_mission_elements();
    if (in_.focus && in_.mission != nullptr) {
      p_ = Projection(box_around(mission_points_), in_.width_px, 10);
    }
    height_ = kTitleHeight + p_.map_height_px() + kLegendHeight;
    thin_ = map_.pipe_count() > kFullDetailPipes;
    if (!mission_points_.empty()) {
      surroundings_ = box_around(mission_points_);
      const double grow =
          std::max(50.0, 0.25 * std::max(surroundings_->max_x - surroundings_->min_x,
                                         surroundings_->max_y - surroundings_->min_y));
      surroundings_->min_x -= grow;
      surroundings_->max_x += grow;
      surroundings_->min_y -= grow;
      surroundings_->max_y += grow;
    }
  }

  Result<std::string> draw() {
    if (Result<void> begun = c_.begin(in_.width_px, height_); !begun.has_value()) {
      return begun.error();
    }
    std::string title = in_.title;
    if (title.empty()) {
      title = map_.name();
      if (in_.mission != nullptr) title += (title.empty() ? "" : ": ") + in_.mission->name;
    }
    c_.text({in_.width_px / 2, 24}, title, {.size = 16, .anchor = Anchor::kMiddle},
            {.id = "title"});
    // Everything on the map is clipped to its area (a focused picture cuts the network off).
    const Rect area{0, kTitleHeight, in_.width_px, p_.map_height_px()};
    c_.begin_group("map", &area);
    choose_manholes();
    pipes();
    if (in_.mission != nullptr) tasks();
    if (in_.mission != nullptr && in_.trace != nullptr) {
      route("driven", in_.trace->driven,
            {.stroke = kDriven, .stroke_width = 7, .stroke_opacity = 0.55});
    }
    if (in_.mission != nullptr && in_.plan != nullptr) {
      route("planned", in_.plan->steps,
            {.stroke = kPlanned, .stroke_width = 2.5, .dash_on = 8, .dash_off = 5});
    }
    // The start under the manholes: a mission often starts next to the exit it ends at.
    if (in_.mission != nullptr) start();
    manholes();
    if (in_.driveability != nullptr) passages();
    if (in_.faults != nullptr) faults();
    if (in_.trace != nullptr) blocked();
    c_.end_group();
    scale_bar();
    legend();
    return c_.finish();
  }

 private:
  // The mission's elements, kept at every level of detail, and the points that bound them.
  void mark_mission_elements() {
    keep_manhole_.assign(map_.manhole_count(), false);
    keep_pipe_.assign(map_.pipe_count(), false);
    if (in_.mission == nullptr) return;
    const Mission& mission = *in_.mission;
    auto manhole = [&](ManholeId m) { keep_manhole_[m.index()] = true; };
    auto pipe = [&](PipeId id) {
      keep_pipe_[id.index()] = true;
      for (const PipeEnd& e : map_.pipe(id).ends) {
        if (e.manhole) manhole(*e.manhole);
      }
      if (const auto line = domain::pipe_line(map_, id)) {
        mission_points_.insert(mission_points_.end(), line->begin(), line->end());
      }
    };
    auto place = [&](const Place& at) {
      if (const auto* m = std::get_if<ManholeId>(&at)) manhole(*m);
      if (const auto* s = std::get_if<PipeSpot>(&at)) pipe(s->pipe);
      if (const auto xy = domain::place_point(map_, at)) mission_points_.push_back(*xy);
    };
    place(mission.start);
    for (const Task& t : mission.tasks) place(t.place);
    for (const auto* steps : {in_.plan != nullptr ? &in_.plan->steps : nullptr,
                              in_.trace != nullptr ? &in_.trace->driven : nullptr}) {
      if (steps == nullptr) continue;
      for (const domain::PlanStep& step : *steps) {
        std::visit(Overloaded{[&](const domain::DrivePipeToManhole& s) { pipe(s.pipe); },
                              [&](const domain::DriveManhole& s) { manhole(s.manhole); },
                              [&](const domain::EnterPipe& s) { pipe(s.pipe); },
                              [&](const domain::TakeWaterSample& s) { pipe(s.pipe); },
                              [&](const domain::GoToPoint& s) { pipe(s.pipe); },
                              [&](const domain::GoToManhole& s) { manhole(s.manhole); },
                              [&](const domain::InspectPipe& s) { pipe(s.pipe); }},
                   step);
      }
    }
    if (in_.trace != nullptr) {
      for (const Blockage& b : in_.trace->blocked) pipe(b.pipe);
      for (const ClosedPassage& c : in_.trace->closed) manhole(c.manhole);
    }
    if (in_.faults != nullptr) {
      for (const hal::Obstacle& o : in_.faults->obstacles) keep_pipe_[o.pipe.index()] = true;
      for (const hal::DangerSpot& d : in_.faults->danger_spots) keep_pipe_[d.pipe.index()] = true;
    }
  }

  bool in_full(MapXY a) const { return !thin_ || (surroundings_ && surroundings_->contains(a)); }

  bool on_picture(Point a, Point b, double pad) const {
    return std::max(a.x, b.x) >= -pad && std::min(a.x, b.x) <= in_.width_px + pad &&
           std::max(a.y, b.y) >= kTitleHeight - pad &&
           std::min(a.y, b.y) <= kTitleHeight + p_.map_height_px() + pad;
  }

  Point manhole_px(ManholeId m) const { return p_(domain::manhole_point(map_, m)); }
  std::optional<Point> pipe_px(PipeId id, double offset_m) const {
    const auto xy = domain::pipe_point(map_, id, offset_m);
    return xy ? std::optional(p_(*xy)) : std::nullopt;
  }
  std::optional<Point> place_px(const Place& place) const {
    const auto xy = domain::place_point(map_, place);
    return xy ? std::optional(p_(*xy)) : std::nullopt;
  }
  double manhole_radius() const { return map_.manhole_count() > 300 ? 1.5 : 4; }

  // Which manholes are drawn (thinned: one a cell, exits first), and where names fit.
  void choose_manholes() {
    const double r = manhole_radius();
    draw_manhole_.assign(map_.manhole_count(), false);
    Grid cells(in_.width_px, height_, 2 * r + 1);
    labels_ = Grid(in_.width_px, height_, 2);
    for (const bool exits : {true, false}) {
      for (ManholeId id : map_.manhole_ids()) {
        const Manhole& m = map_.manhole(id);
        if (m.exit != exits) continue;
        const Point c = manhole_px(id);
        if (!on_picture(c, c, 10) && !keep_manhole_[id.index()]) continue;
        const Rect dot{c.x - r, c.y - r, 2 * r, 2 * r};
        const bool full = keep_manhole_[id.index()] || in_full(domain::manhole_point(map_, id));
        // Thinned: a manhole (an exit: its larger square) with room around it, or none.
        const double room = exits ? r + 5 : r + 2;
        if (!full && !cells.free({c.x - room, c.y - room, 2 * room, 2 * room})) continue;
        cells.take(dot);
        labels_->take(dot);
        draw_manhole_[id.index()] = true;
      }
    }
    // Names of the manholes drawn, where they fit.
    manhole_label_.assign(map_.manhole_count(), false);
    for (ManholeId id : map_.manhole_ids()) {
      if (!draw_manhole_[id.index()]) continue;
      const Point c = manhole_px(id);
      // Below right of its own dot, clear of it by a grid cell at least.
      const Rect box{c.x + r + 3, c.y + r + 2, text_width(map_.manhole(id).name, 11), 8};
      if (fits(box)) manhole_label_[id.index()] = true;
    }
  }

  // Whether a name fits in `box` (and takes it if so): on the map and over nothing taken.
  bool fits(const Rect& box) {
    if (box.x < 0 || box.x + box.width > in_.width_px || box.y < kTitleHeight ||
        box.y + box.height > kTitleHeight + p_.map_height_px() || !labels_->free(box)) {
      return false;
    }
    labels_->take(box);
    return true;
  }

  Colour pipe_colour(PipeId id, const Pipe& pipe) const {
    if (in_.driveability != nullptr) {
      const std::string_view why = domain::why_not_driveable(id, *in_.driveability);
      if (why.empty()) return kPipeColour;
      if (why == "too narrow") return kTooNarrow;
      if (why == "too wide") return kTooWide;
      if (why == "cut off by a closure") return kCutOff;
      return kUndrivable;
    }
    if (in_.mission == nullptr) return kPipeColour;
    const RobotProfile& r = in_.mission->profile;
    const bool drivable =
        pipe.diameter_m >= r.min_pipe_diameter_m && pipe.diameter_m <= r.max_pipe_diameter_m;
    return drivable ? kPipeColour : kUndrivable;
  }

  void pipes() {
    c_.begin_group("pipes");
    // Pipes drawn over the same pixels, by their rounded ends (thinned parts only).
    std::unordered_set<std::uint64_t> drawn;
    const auto pixel = [](Point a) {
      return (static_cast<std::uint64_t>(std::lround(a.x) & 0xffff) << 16) |
             static_cast<std::uint64_t>(std::lround(a.y) & 0xffff);
    };
    std::string title;
    for (PipeId id : map_.pipe_ids()) {
      const Pipe& pipe = map_.pipe(id);
      const auto line = domain::pipe_line(map_, id);
      if (!line) continue;
      const Point a = p_((*line)[0]);
      const Point b = p_((*line)[1]);
      const bool keep = keep_pipe_[id.index()];
      if (!keep && thin_ && !on_picture(a, b, 10)) continue;
      double width = std::clamp(pipe.diameter_m * 6, 0.8, 8.0);
      if (!keep && !in_full((*line)[0]) && !in_full((*line)[1])) {
        if (std::hypot(b.x - a.x, b.y - a.y) < 1) continue;
        width = std::min(width, 1.2);
        const std::uint64_t pa = pixel(a);
        const std::uint64_t pb = pixel(b);
        if (!drawn.insert(std::min(pa, pb) << 32 | std::max(pa, pb)).second) continue;
      }
      if (tags_) {
        title = pipe.name + ", " + f1(pipe.length_m) + " m, DN " +
                std::to_string(std::lround(pipe.diameter_m * 1000));
        if (in_.driveability != nullptr) {
          const std::string_view why = domain::why_not_driveable(id, *in_.driveability);
          if (!why.empty()) title += std::string(", ") + std::string(why);
        }
      }
      c_.line(a, b, {.stroke = pipe_colour(id, pipe), .stroke_width = width},
              {.cls = "pipe", .title = title});
      const double length_px = std::hypot(b.x - a.x, b.y - a.y);
      const double label_width = text_width(pipe.name, 9);
      const Point mid{(a.x + b.x) / 2 + 4, (a.y + b.y) / 2 - 4};
      if (length_px >= label_width + 8 && fits({mid.x, mid.y - 8, label_width, 9})) {
        c_.text(mid, pipe.name, {.size = 9, .colour = Colour::rgb(0x44617f)},
                {.cls = "pipe-label"});
      }
    }
    c_.end_group();
  }

  void manholes() {
    c_.begin_group("manholes");
    const double r = manhole_radius();
    std::string title;
    for (ManholeId id : map_.manhole_ids()) {
      if (!draw_manhole_[id.index()]) continue;
      const Manhole& m = map_.manhole(id);
      const Point c = manhole_px(id);
      if (tags_) title = m.exit ? m.name + " (exit)" : m.name;
      if (m.exit) {
        c_.rect({c.x - r - 2, c.y - r - 2, 2 * r + 4, 2 * r + 4}, {.fill = kExit, .stroke = kBlack},
                {.cls = "exit", .title = title});
      } else {
        c_.circle(c, r, {.fill = kWhite, .stroke = kBlack}, {.cls = "manhole", .title = title});
      }
      if (manhole_label_[id.index()]) {
        c_.text({c.x + r + 3, c.y + r + 9}, m.name, {}, {.cls = "manhole-label"});
      }
    }
    c_.end_group();
  }

  void tasks() {
    const Mission& mission = *in_.mission;
    c_.begin_group("tasks");
    for (const Task& t : mission.tasks) {
      const bool done = in_.trace != nullptr &&
                        std::find(in_.trace->tasks_done.begin(), in_.trace->tasks_done.end(),
                                  t.name) != in_.trace->tasks_done.end();
      const Colour fill = done ? kDriven : kTodo;
      const std::string tip = t.name + (done ? " (done)" : "") + (t.final ? ", final" : "");
      if (t.kind == TaskKind::kInspectPipe) {
        const auto line = domain::pipe_line(map_, std::get<PipeSpot>(t.place).pipe);
        if (!line) continue;
        c_.line(p_((*line)[0]), p_((*line)[1]),
                {.stroke = fill, .stroke_width = 10, .stroke_opacity = 0.45},
                {.cls = "task inspection", .title = tip});
        continue;
      }
      const auto at = place_px(t.place);
      if (!at) continue;
      const Point c = *at;
      if (t.kind == TaskKind::kTakeWaterSample) {
        const std::array<Point, 3> triangle{Point{c.x, c.y - 7}, Point{c.x + 6, c.y + 5},
                                            Point{c.x - 6, c.y + 5}};
        c_.polygon(triangle, {.fill = fill, .stroke = kBlack},
                   {.cls = "task sample", .title = tip});
      } else {
        const std::array<Point, 4> diamond{Point{c.x, c.y - 7}, Point{c.x + 7, c.y},
                                           Point{c.x, c.y + 7}, Point{c.x - 7, c.y}};
        c_.polygon(diamond, {.fill = fill, .stroke = kBlack},
                   {.cls = t.final ? "task goto final" : "task goto", .title = tip});
      }
    }
    c_.end_group();
  }

  void route(const char* id, const std::vector<domain::PlanStep>& steps, const Paint& paint) {
    std::vector<Point> points;
    for (const MapXY& xy : domain::route_points(map_, *in_.mission, steps)) {
      points.push_back(p_(xy));
    }
    const std::string title =
        std::string(id) + " route, " + std::to_string(steps.size()) + " steps";
    c_.polyline(points, paint, {.id = id, .cls = "route", .title = title});
  }

  void cross(Point c, const char* cls, Colour colour, const std::string& tip) {
    const std::array<Point, 4> lines{Point{c.x - 6, c.y - 6}, Point{c.x + 6, c.y + 6},
                                     Point{c.x - 6, c.y + 6}, Point{c.x + 6, c.y - 6}};
    c_.segments(lines, {.stroke = colour, .stroke_width = 3}, {.cls = cls, .title = tip});
  }

  void passages() {
    c_.begin_group("passages");
    for (const domain::PassageLimit& p : in_.driveability->passages) {
      const std::string tip = "passage over the robot's limits in " + map_.manhole(p.manhole).name +
                              (p.motion_reason.empty() ? "" : ": " + p.motion_reason);
      c_.circle(manhole_px(p.manhole), 6, {.stroke = kPassage, .stroke_width = 2},
                {.cls = "passage-limit", .title = tip});
    }
    c_.end_group();
  }

  void faults() {
    const hal::FaultScenario& f = *in_.faults;
    c_.begin_group("faults");
    for (const hal::Obstacle& o : f.obstacles) {
      const auto c = pipe_px(o.pipe, o.offset_m);
      if (!c) continue;
      c_.rect({c->x - 3.5, c->y - 3.5, 7, 7},
              {.fill = o.kind == hal::ObstacleKind::kPermanent ? kBlack : Colour::rgb(0x999999)},
              {.cls = "fault obstacle",
               .title = "obstacle in " + map_.pipe(o.pipe).name + " at " + f1(o.offset_m) + " m (" +
                        std::string(hal::to_string(o.kind)) + ")"});
    }
    for (const hal::DangerSpot& d : f.danger_spots) {
      const auto c = pipe_px(d.pipe, d.offset_m);
      if (!c) continue;
      c_.circle(*c, 4, {.fill = kDanger},
                {.cls = "fault danger",
                 .title = "danger in " + map_.pipe(d.pipe).name + " at " + f1(d.offset_m) + " m"});
    }
    for (const hal::DangerousPassage& p : f.dangerous_passages) {
      c_.circle(manhole_px(p.manhole), 9, {.stroke = kDanger, .stroke_width = 2},
                {.cls = "fault passage",
                 .title = "dangerous passage in " + map_.manhole(p.manhole).name});
    }
    c_.end_group();
  }

  void blocked() {
    c_.begin_group("blocked");
    for (const Blockage& b : in_.trace->blocked) {
      if (const auto c = pipe_px(b.pipe, b.offset_m)) {
        cross(*c, "blocked", kBlocked,
              "found blocked: " + map_.pipe(b.pipe).name + " at " + f1(b.offset_m) + " m");
      }
    }
    for (const ClosedPassage& c : in_.trace->closed) {
      c_.circle(manhole_px(c.manhole), 11, {.stroke = kBlocked, .stroke_width = 3},
                {.cls = "closed", .title = "passage closed in " + map_.manhole(c.manhole).name});
    }
    c_.end_group();
  }

  void start() {
    const auto at = place_px(in_.mission->start);
    if (!at) return;
    c_.begin_group("start");
    c_.circle(*at, 8, {.fill = kPlanned});
    c_.text({at->x, at->y + 4}, "S", {.colour = kWhite, .anchor = Anchor::kMiddle, .bold = true});
    c_.end_group();
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
    c_.begin_group("scale");
    c_.line({x, y}, {x + px, y}, {.stroke = kBlack, .stroke_width = 3});
    c_.text({x + px / 2, y - 5},
            (length >= 1 ? std::to_string(std::lround(length)) : f1(length)) + " m",
            {.anchor = Anchor::kMiddle});
    c_.end_group();
  }

  // One legend entry: a symbol drawn in a 28 x 14 pixel box at (x, y - 7), and its text.
  template <typename Symbol>
  void key(Symbol symbol, const std::string& text) {
    const double x = kMargin + key_column_ * 250;
    c_.begin_group("");
    symbol(x, key_y_);
    c_.text({x + 34, key_y_ + 4}, text, {});
    c_.end_group();
    if (++key_column_ == 3) {
      key_column_ = 0;
      key_y_ += 20;
    }
  }

  void line_key(const Paint& paint, const std::string& text) {
    key([&](double x, double y) { c_.line({x, y}, {x + 28, y}, paint); }, text);
  }

  void legend() {
    key_y_ = kTitleHeight + p_.map_height_px() + 20;
    key_column_ = 0;
    c_.begin_group("legend");
    if (in_.driveability != nullptr) {
      line_key({.stroke = kPipeColour, .stroke_width = 3}, "pipe the robot can drive");
      line_key({.stroke = kTooNarrow, .stroke_width = 3}, "too narrow");
      line_key({.stroke = kTooWide, .stroke_width = 3}, "too wide");
      line_key({.stroke = kUndrivable, .stroke_width = 3}, "unreachable");
      line_key({.stroke = kCutOff, .stroke_width = 3}, "cut off by a closure");
      key(
          [&](double x, double y) {
            c_.circle({x + 14, y}, 6, {.stroke = kPassage, .stroke_width = 2});
          },
          "passage over the robot's limits");
    } else {
      line_key({.stroke = kPipeColour, .stroke_width = 3}, "pipe (width by diameter)");
      line_key({.stroke = kUndrivable, .stroke_width = 3}, "pipe the robot cannot drive");
    }
    key(
        [&](double x, double y) {
          c_.circle({x + 14, y}, 4, {.fill = kWhite, .stroke = kBlack});
        },
        "manhole");
    key(
        [&](double x, double y) {
          c_.rect({x + 8, y - 6, 12, 12}, {.fill = kExit, .stroke = kBlack});
        },
        "exit");
    if (in_.mission != nullptr) {
      key([&](double x, double y) { c_.circle({x + 14, y}, 7, {.fill = kPlanned}); }, "start");
      line_key({.stroke = kTodo, .stroke_width = 8, .stroke_opacity = 0.45},
               "inspection (green: done)");
      key(
          [&](double x, double y) {
            const std::array<Point, 3> t{Point{x + 14, y - 7}, Point{x + 20, y + 5},
                                         Point{x + 8, y + 5}};
            c_.polygon(t, {.fill = kTodo, .stroke = kBlack});
          },
          "water sample (green: done)");
      key(
          [&](double x, double y) {
            const std::array<Point, 4> d{Point{x + 14, y - 7}, Point{x + 21, y},
                                         Point{x + 14, y + 7}, Point{x + 7, y}};
            c_.polygon(d, {.fill = kTodo, .stroke = kBlack});
          },
          "go-to task or end point");
    }
    if (in_.plan != nullptr) {
      line_key({.stroke = kPlanned, .stroke_width = 2.5, .dash_on = 8, .dash_off = 5},
               "planned route");
    }
    if (in_.trace != nullptr) {
      line_key({.stroke = kDriven, .stroke_width = 7, .stroke_opacity = 0.55}, "route driven");
      key(
          [&](double x, double y) {
            const std::array<Point, 4> s{Point{x + 8, y - 6}, Point{x + 20, y + 6},
                                         Point{x + 8, y + 6}, Point{x + 20, y - 6}};
            c_.segments(s, {.stroke = kBlocked, .stroke_width = 3});
          },
          "found blocked / dangerous");
    }
    if (in_.faults != nullptr) {
      key(
          [&](double x, double y) {
            c_.rect({x + 10, y - 4, 7, 7}, {.fill = kBlack});
          },
          "hidden obstacle (grey: transient)");
      key(
          [&](double x, double y) {
            c_.circle({x + 14, y}, 4, {.fill = kDanger});
          },
          "hidden danger spot");
    }
    if (key_column_ != 0) key_y_ += 20;
    if (in_.trace != nullptr && !in_.trace->outcome.empty()) {
      c_.text({kMargin, key_y_ + 6},
              in_.trace->outcome + "; tasks done: " + std::to_string(in_.trace->tasks_done.size()) +
                  ", replans: " + std::to_string(in_.trace->replans),
              {}, {.id = "outcome"});
    }
    c_.end_group();
  }

  const RenderInput& in_;
  const SewerMap& map_;
  Canvas& c_;
  Projection p_;
  double height_ = 0;
  bool tags_ = true;
  bool thin_ = false;
  std::optional<Box> surroundings_;
  std::vector<MapXY> mission_points_;
  std::vector<bool> keep_manhole_;
  std::vector<bool> keep_pipe_;
  std::vector<bool> draw_manhole_;
  std::vector<bool> manhole_label_;
  std::optional<Grid> labels_;
  double key_y_ = 0;
  int key_column_ = 0;
};

}  // namespace

Result<std::string> draw_map(const RenderInput& input, Canvas& canvas) {
  SEWER_CHECK(input.map != nullptr, "draw_map needs a map");
  return Scene(input, canvas).draw();
}

std::string render_map_svg(const RenderInput& input) {
  SvgCanvas svg;
  // An SVG canvas takes any size.
  return draw_map(input, svg).value();
}

}  // namespace sewerplan::render
