// SPDX-License-Identifier: MIT
// OmplHeadPathPlanner (ompl_head_path_planner.h): the head's pose in the Dubins space, RRT, a
// seeded sampler. The only file of sewerplan that includes OMPL (STYLE.md, fusion/).
#include "sewerplan/motion/ompl_head_path_planner.h"

#include <cmath>
#include <cstdlib>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <ompl/base/PlannerStatus.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateSampler.h>
#include <ompl/base/spaces/DubinsStateSpace.h>
#include <ompl/datastructures/NearestNeighborsLinear.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/util/Console.h>
#include <ompl/util/Exception.h>
#include <ompl/util/RandomNumbers.h>

namespace sewerplan::motion {
namespace {

using fusion::HeadPath;
using fusion::HeadPathProblem;
using fusion::HeadPose;
using fusion::in_free_space;
using fusion::PassageGeometry;
using fusion::TurnPlannerOptions;

namespace ob = ompl::base;
namespace og = ompl::geometric;

using HeadState = ob::ScopedState<ob::DubinsStateSpace>;

constexpr double kDensify_m = 0.01;
constexpr double kCheckResolution_m = 0.005;

// Uniform samples in the space's bounds from an RNG of its own, seeded, so that planning does not
// depend on OMPL's process-wide seed or on what was planned before.
class SeededSampler : public ob::StateSampler {
 public:
  SeededSampler(const ob::StateSpace* space, std::uint32_t seed) : ob::StateSampler(space) {
    rng_.setLocalSeed(seed);
  }

  void sampleUniform(ob::State* state) override {
    const ob::RealVectorBounds& b = space_->as<ob::SE2StateSpace>()->getBounds();
    auto* s = state->as<ob::SE2StateSpace::StateType>();
    s->setXY(rng_.uniformReal(b.low[0], b.high[0]), rng_.uniformReal(b.low[1], b.high[1]));
    s->setYaw(rng_.uniformReal(-std::numbers::pi, std::numbers::pi));
  }

  void sampleUniformNear(ob::State* state, const ob::State* near, double distance) override {
    const auto* n = near->as<ob::SE2StateSpace::StateType>();
    auto* s = state->as<ob::SE2StateSpace::StateType>();
    s->setXY(n->getX() + rng_.uniformReal(-distance, distance),
             n->getY() + rng_.uniformReal(-distance, distance));
    s->setYaw(n->getYaw() + rng_.uniformReal(-distance, distance));
    space_->enforceBounds(state);
  }

  void sampleGaussian(ob::State* state, const ob::State* mean, double std_dev) override {
    const auto* n = mean->as<ob::SE2StateSpace::StateType>();
    auto* s = state->as<ob::SE2StateSpace::StateType>();
    s->setXY(rng_.gaussian(n->getX(), std_dev), rng_.gaussian(n->getY(), std_dev));
    s->setYaw(rng_.gaussian(n->getYaw(), std_dev));
    space_->enforceBounds(state);
  }
};

// RRT draws its goal bias from an RNG of its own, seeded from OMPL's process-wide seed: seed it
// with ours.
class SeededRrt : public og::RRT {
 public:
  SeededRrt(const ob::SpaceInformationPtr& si, std::uint32_t seed) : og::RRT(si) {
    rng_.setLocalSeed(seed);
  }
};

HeadPose pose_of(const HeadState& s) { return HeadPose{s->getX(), s->getY(), s->getYaw()}; }

// Drops every state that a direct, valid Dubins motion can skip, greedily from the start: the
// same path every time (OMPL's shortcutting samples at random). Its motion checks are most of a
// plan's time after RRT (up to tens of ms: bench/fusion/passage_precompute_bench.cc,
// BM_PrecomputeStopCheckGap), so `stop` is asked before each; when it fires the path is partial.
std::vector<HeadState> shortened(const ob::SpaceInformation& si, const std::vector<HeadState>& in,
                                 const StopCondition& stop) {
  std::vector<HeadState> out{in.front()};
  std::size_t i = 0;
  while (i + 1 < in.size()) {
    std::size_t j = in.size() - 1;
    while (j > i + 1 && !stop.interrupted() && !si.checkMotion(in[i].get(), in[j].get())) --j;
    out.push_back(in[j]);
    i = j;
  }
  return out;
}

std::vector<HeadPose> densified(const ob::StateSpacePtr& space,
                                const std::vector<HeadState>& path) {
  std::vector<HeadPose> poses{pose_of(path.front())};
  HeadState between(space);
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    const double d = space->distance(path[k].get(), path[k + 1].get());
    const auto n = static_cast<std::size_t>(std::ceil(d / kDensify_m));
    for (std::size_t i = 1; i <= n; ++i) {
      space->interpolate(path[k].get(), path[k + 1].get(),
                         static_cast<double>(i) / static_cast<double>(n), between.get());
      poses.push_back(pose_of(between));
    }
  }
  return poses;
}

// The head's space over the manhole's square, sampled by a SeededSampler.
std::shared_ptr<ob::DubinsStateSpace> head_space(const HeadPathProblem& problem,
                                                 const TurnPlannerOptions& options) {
  const double r = problem.geometry.manhole_diameter_m / 2 + problem.pipe_reach_m + 0.05;
  auto space = std::make_shared<ob::DubinsStateSpace>(problem.turn_radius_m);
  ob::RealVectorBounds bounds(2);
  bounds.setLow(-r);
  bounds.setHigh(r);
  space->setBounds(bounds);
  const std::uint32_t seed = options.seed;
  space->setStateSamplerAllocator(
      [seed](const ob::StateSpace* s) { return std::make_shared<SeededSampler>(s, seed); });
  space->setup();
  return space;
}

}  // namespace

Result<void> OmplHeadPathPlanner::check_space(const HeadPathProblem& problem,
                                              const TurnPlannerOptions& options) const {
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  try {
    head_space(problem, options)->sanityChecks();
  } catch (const ompl::Exception& e) {
    return Error{ErrorCode::kInvalidArgument, e.what()};
  }
  return {};
}

Result<HeadPath> OmplHeadPathPlanner::plan(const HeadPathProblem& problem,
                                           const TurnPlannerOptions& options,
                                           const StopCondition& stop) const {
  ompl::msg::setLogLevel(std::getenv("SEWERPLAN_OMPL_DEBUG") ? ompl::msg::LOG_DEBUG
                                                             : ompl::msg::LOG_ERROR);
  const PassageGeometry g = problem.geometry;
  const double clearance = problem.clearance_m;
  const double pipe_clearance = problem.pipe_clearance_m;
  // The setup before the first RRT iteration is asked the stop between its parts: the first in a
  // process took 0.8 to 1.3 ms without a check (issue 14).
  auto space = head_space(problem, options);
  if (auto stopped = stop.interrupted()) return stopped_error(*stopped, "the motion planner");
  const std::uint32_t seed = options.seed;

  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker(
      [g, clearance, pipe_clearance, raw = si.get()](const ob::State* state) {
        const auto* s = state->as<ob::SE2StateSpace::StateType>();
        return raw->satisfiesBounds(state) &&
               in_free_space(g, s->getX(), s->getY(), clearance, pipe_clearance);
      });
  si->setMotionValidator(std::make_shared<ob::DubinsMotionValidator>(si.get()));
  si->setStateValidityCheckingResolution(kCheckResolution_m / space->getMaximumExtent());
  si->setup();
  if (auto stopped = stop.interrupted()) return stopped_error(*stopped, "the motion planner");

  HeadState start(space);
  start->setXY(problem.start.x_m, problem.start.y_m);
  start->setYaw(problem.start.heading_rad);
  HeadState goal(space);
  goal->setXY(problem.goal.x_m, problem.goal.y_m);
  goal->setYaw(problem.goal.heading_rad);

  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  pdef->setStartAndGoalStates(start, goal, 1e-6);
  // RRT, not RRT-Connect: OMPL 1.5's RRT-Connect grows its goal tree by interpolating forwards
  // from the goal, which in a forward-only Dubins space leaves the goal the wrong way.
  auto planner = std::make_shared<SeededRrt>(si, seed);
  planner->setProblemDefinition(pdef);
  planner->setNearestNeighbors<ompl::NearestNeighborsLinear>();
  planner->setRange(0.3);
  planner->setGoalBias(0.2);
  planner->setup();  // else the first solve() does it, before its first iteration's check
  if (auto stopped = stop.interrupted()) return stopped_error(*stopped, "the motion planner");

  // A count of iterations, not a time: the same result on any machine. Our stop condition (a
  // cancel, the caller's deadline) ends it too, asked at every iteration.
  HeadPath result;
  const std::uint32_t limit = options.max_iterations;
  std::uint32_t& count = result.iterations;
  std::optional<SearchStatus> stopped;
  const ob::PlannerStatus status = planner->solve(ob::PlannerTerminationCondition([&] {
    if (++count > limit) return true;
    stopped = stop.interrupted();
    return stopped.has_value();
  }));
  if (count > limit) count = limit;
  switch (ob::PlannerStatus::StatusType(status)) {
    case ob::PlannerStatus::EXACT_SOLUTION:
      break;
    case ob::PlannerStatus::TIMEOUT:
    case ob::PlannerStatus::APPROXIMATE_SOLUTION:
      if (stopped) return stopped_error(*stopped, "the motion planner");
      return result;  // not found within the iterations
    case ob::PlannerStatus::UNKNOWN:
    case ob::PlannerStatus::INVALID_START:
    case ob::PlannerStatus::INVALID_GOAL:
    case ob::PlannerStatus::UNRECOGNIZED_GOAL_TYPE:
    case ob::PlannerStatus::CRASH:
    case ob::PlannerStatus::ABORT:
    case ob::PlannerStatus::TYPE_COUNT:
      return Error{ErrorCode::kInvalidArgument,
                   "OMPL could not plan the passage (" + status.asString() + ")"};
  }
  const auto* path = pdef->getSolutionPath()->as<og::PathGeometric>();
  std::vector<HeadState> states;
  for (unsigned i = 0; i < path->getStateCount(); ++i) {
    const ob::State* s = path->getState(i);
    HeadState copy(space);
    copy = s;
    states.push_back(copy);
  }
  std::vector<HeadState> path_states = shortened(*si, states, stop);
  if (auto late = stop.interrupted()) return stopped_error(*late, "the motion planner");
  result.found = true;
  result.poses = densified(space, path_states);
  return result;
}

}  // namespace sewerplan::motion
