// SPDX-License-Identifier: MIT
// Scoring a robot's localisation and measured map against the true world (world_score.h).
#include "sewerplan/campaign/world_score.h"

#include <algorithm>
#include <cmath>
#include <variant>

namespace sewerplan::campaign {
namespace {

template <typename Id>
void add_once(std::vector<Id>& ids, Id id) {
  if (std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
}

template <typename Id>
bool contains(const std::vector<Id>& ids, const std::optional<Id>& id) {
  return id && std::find(ids.begin(), ids.end(), *id) != ids.end();
}

bool drove_through(const std::vector<MouthOf>& mouths, const Discrepancy& d) {
  return d.manhole && d.slot &&
         std::find(mouths.begin(), mouths.end(), MouthOf{*d.manhole, *d.slot}) != mouths.end();
}

}  // namespace

std::optional<double> percent(std::size_t part, std::size_t whole) {
  if (whole == 0) return std::nullopt;
  return 100.0 * static_cast<double>(part) / static_cast<double>(whole);
}

bool arrival_correct(const SewerMap& map, const hal::SimPose& true_pose,
                     std::string_view believed_manhole) {
  std::optional<ManholeId> truly;
  if (const auto* at = std::get_if<hal::AtSlot>(&true_pose)) truly = at->manhole;
  if (const auto* in = std::get_if<hal::InManhole>(&true_pose)) truly = in->manhole;
  // In a pipe (a false detection), or at a manhole only the world has (appended after the map's).
  if (!truly || truly->index() >= map.manhole_count()) return believed_manhole.empty();
  return map.manhole(*truly).name == believed_manhole;
}

std::vector<double> length_errors(const SewerMap& map, const hal::TrueWorld& truth,
                                  const MapMeasurements& measurements) {
  std::vector<double> errors;
  errors.reserve(measurements.pipes.size());
  for (const PipeMeasurement& p : measurements.pipes) {
    if (p.pipe.index() >= map.pipe_count()) continue;  // not of this map: nothing to score
    const double true_m = hal::world_length_m(truth, p.pipe);
    // The corrected map's length (map_measurements.h): the measurement weighed with the map's.
    const double corrected_m = corrected_length_m(map.pipe(p.pipe).length_m, p.length_m);
    errors.push_back((corrected_m - true_m) / true_m);
  }
  return errors;
}

double rms(const std::vector<double>& values) {
  if (values.empty()) return 0;
  double sum = 0;
  for (double v : values) sum += v * v;
  return std::sqrt(sum / static_cast<double>(values.size()));
}

bool within_reach(const Discrepancy& seeded, const Reach& reach) {
  using Kind = Discrepancy::Kind;
  switch (seeded.kind) {
    case Kind::kLengthOff:
    case Kind::kDiameterSmaller:
      return contains(reach.pipes_driven_whole, seeded.pipe);
    case Kind::kUnmappedJunction:
      return contains(reach.junctions_arrived, seeded.pipe);
    case Kind::kDirectionOff:
      return drove_through(reach.mouths_driven, seeded);
    case Kind::kUnmappedLateral:
    case Kind::kMissingLateral:
      return contains(reach.manholes_arrived, seeded.manhole);
    case Kind::kPositionOff:
      return false;
  }
  return false;
}

DiscrepancyScore score_discrepancies(const std::vector<Discrepancy>& seeded,
                                     const std::vector<FoundDiscrepancy>& reported,
                                     const Reach& reach) {
  DiscrepancyScore s;
  const auto of = [&](Discrepancy::Kind kind) -> KindScore& {
    return s.by_kind[static_cast<std::size_t>(kind)];
  };
  s.reported = reported.size();
  for (const Discrepancy& d : seeded) {
    if (!within_reach(d, reach)) continue;
    ++s.in_reach;
    ++of(d.kind).in_reach;
    if (std::any_of(reported.begin(), reported.end(),
                    [&](const FoundDiscrepancy& r) { return same_difference(r.discrepancy, d); })) {
      ++s.found;
      ++of(d.kind).found;
    }
  }
  for (const FoundDiscrepancy& r : reported) {
    ++of(r.discrepancy.kind).reported;
    if (std::none_of(seeded.begin(), seeded.end(),
                     [&](const Discrepancy& d) { return same_difference(r.discrepancy, d); })) {
      ++s.false_reports;
      ++of(r.discrepancy.kind).false_reports;
    }
  }
  return s;
}

WorldScorer::WorldScorer(const SewerMap& map, const hal::TrueWorld& truth,
                         const hal::SimRobot& robot)
    : map_(map),
      truth_(truth),
      robot_(robot),
      measurer_(map, MeasurementSource{.robot = "campaign", .mission = "", .date = ""}) {
  // A robot that starts in a pipe comes out of it at its first arrival.
  if (const auto* in = std::get_if<hal::InPipe>(&robot.pose())) in_pipe_ = in->pipe;
}

void WorldScorer::watch(executor::Executor& executor) {
  executor.subscribe([this](const executor::Event& event) {
    const auto* arrival = std::get_if<executor::ArrivalEvent>(&event.what);
    if (arrival == nullptr) return;
    ++arrivals_;
    if (arrival_correct(map_, robot_.pose(), arrival->manhole)) ++correct_;
  });
  executor.subscribe_jobs(measurer_.observer());
  executor.subscribe_jobs([this](const executor::JobSeen& seen) { on_job(seen); });
}

void WorldScorer::through_unseen(PipeId from, PipeId to) {
  const SewerMap& world = truth_.world;
  for (const PipeEnd& a : world.pipe(from).ends) {
    for (const PipeEnd& b : world.pipe(to).ends) {
      if (!a.manhole || a.manhole != b.manhole || a.manhole->index() >= map_.manhole_count()) {
        continue;
      }
      add_once(reach_.mouths_driven, MouthOf{*a.manhole, a.slot});
      add_once(reach_.mouths_driven, MouthOf{*b.manhole, b.slot});
      return;
    }
  }
}

std::optional<PipeId> WorldScorer::map_pipe(PipeId world_pipe) const {
  if (world_pipe.index() >= map_.pipe_count()) return std::nullopt;  // a split's rest, a lateral
  for (const hal::PipeSplit& s : truth_.splits) {
    if (s.pipe == world_pipe) return std::nullopt;  // only a piece of the map's pipe
  }
  return world_pipe;
}

void WorldScorer::on_job(const executor::JobSeen& seen) {
  (void)seen;  // the truth is the simulated robot's pose, not what the controller believes
  const SewerMap& world = truth_.world;
  const hal::SimPose& pose = robot_.pose();
  if (const auto* at = std::get_if<hal::AtSlot>(&pose)) {
    const Slot& slot = world.slot(at->manhole, at->slot);
    const Mouth here{slot.pipe, slot.pipe_end};
    const bool moved =
        !last_mouth_ || last_mouth_->pipe != here.pipe || last_mouth_->end != here.end;
    // Out of the pipe into the manhole through this mouth: from anywhere in the pipe, or driven
    // mouth to mouth in one job.
    const bool out_of_pipe =
        in_pipe_ == here.pipe || (last_mouth_ && last_mouth_->pipe == here.pipe);
    in_pipe_.reset();
    if (!moved) return;  // still at the mouth it entered by or arrived at
    if (out_of_pipe && at->manhole.index() < map_.manhole_count()) {
      add_once(reach_.mouths_driven, MouthOf{at->manhole, at->slot});
    }
    if (at->manhole.index() < map_.manhole_count()) {
      add_once(reach_.manholes_arrived, at->manhole);
    } else {
      for (const hal::PipeSplit& s : truth_.splits) {
        if (s.pipe == slot.pipe || s.rest == slot.pipe) add_once(reach_.junctions_arrived, s.pipe);
      }
    }
    if (last_mouth_ && last_mouth_->pipe == here.pipe) {
      if (const std::optional<PipeId> p = map_pipe(here.pipe)) {
        add_once(reach_.pipes_driven_whole, *p);
      }
    }
    last_mouth_ = here;
    return;
  }
  if (const auto* in = std::get_if<hal::InPipe>(&pose)) {
    const Pipe& pipe = world.pipe(in->pipe);
    // From one pipe into another in one job: through the manhole they share, unseen.
    if (in_pipe_ && *in_pipe_ != in->pipe) through_unseen(*in_pipe_, in->pipe);
    in_pipe_ = in->pipe;
    for (std::uint8_t e = 0; e < 2; ++e) {
      const double end_m = e == 0 ? 0.0 : pipe.length_m;
      if (pipe.ends[e].manhole && std::abs(in->offset_m - end_m) <= 1e-9) {
        last_mouth_ = Mouth{in->pipe, e};  // entered the pipe at this mouth
        if (pipe.ends[e].manhole->index() < map_.manhole_count()) {
          add_once(reach_.mouths_driven, MouthOf{*pipe.ends[e].manhole, pipe.ends[e].slot});
        }
        return;
      }
    }
    if (last_mouth_ && last_mouth_->pipe != in->pipe) last_mouth_.reset();
    return;
  }
  in_pipe_.reset();
  last_mouth_.reset();  // in a manhole, at none of its mouths
}

WorldScore WorldScorer::score() const {
  MapMeasurements measured = measurer_.measurements();
  measured.discrepancies = discrepancies(measured, map_);
  const std::vector<double> errors = length_errors(map_, truth_, measured);
  const DiscrepancyScore d = score_discrepancies(truth_.seeded, measured.discrepancies, reach_);
  return WorldScore{.arrivals = arrivals_,
                    .correct_arrivals = correct_,
                    .pipes_measured = errors.size(),
                    .length_rms_pct = 100 * rms(errors),
                    .seeded_in_reach = d.in_reach,
                    .found = d.found,
                    .reported = d.reported,
                    .false_reports = d.false_reports,
                    .by_kind = d.by_kind};
}

}  // namespace sewerplan::campaign
