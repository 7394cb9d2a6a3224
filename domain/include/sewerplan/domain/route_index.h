// SPDX-License-Identifier: MIT
// RouteIndex: a map's routing index for one robot profile and motion table, built once and kept
// in a file beside the map (issue 35; docs/formats/route-index.md, docs/benchmarks.md).
//
// The compile takes its routes from a contraction hierarchy over the robot's moves on the map
// (CompileCache::RoutingIndex). Building it takes seconds at 100,000 manholes and a minute at a
// million, so a process that plans once (`sewerplan plan`) would pay that every time: a RouteIndex
// is that hierarchy as a value that can be built once (`sewerplan index build`), saved, loaded and
// handed to a CompileCache (CompileCache::use_route_index), whose compiles then take their routes
// from it without building one. It is the motion table's sibling (docs/motion.md): made by a
// command, kept as MAP.route-index.bin beside the map, and never used stale.
//
// Never stale: the index carries a fingerprint of the graph it was built over, the moves out of
// every position of the map and their costs for that robot and motion table, as the compile
// generates them (GraphCore's adjacency, FNV-1a 64 over its arrays). A compile checks it against
// the graph of its own map, robot and table before using the index, and fails (kInvalidArgument)
// where they differ, whatever changed: the map, the profile, the table, or the rules that turn
// them into moves in another version of sewerplan.
//
//   Result<RouteIndex> index = RouteIndex::build(map, mission.profile, mission.passage_motion);
//   index->save(default_route_index_path("ais.json"));  // ais.route-index.bin
//   ...
//   Result<RouteIndex> loaded = RouteIndex::load("ais.route-index.bin");  // every byte checked
//   CompileCache cache;
//   cache.use_route_index(*loaded);
//   auto task = compile_sewer_task(map, mission, progress, {.cache = &cache});  // no build
//
// A RouteIndex is immutable and cheap to copy (its copies share the hierarchy): safe to use from
// any number of threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <utility>

#include "sewerplan/core/passage_motion.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/core/sewer_map.h"
#include "sewerplan/core/stop_condition.h"

namespace sewerplan::domain {

struct RouteIndexStatistics {
  std::size_t nodes = 0;      // positions of the map (the compile's graph without extra spots)
  std::size_t moves = 0;      // of the graph, parallel moves merged
  std::size_t shortcuts = 0;  // added by the contraction
  std::size_t edges = 0;      // in the hierarchy: moves and shortcuts, each once
  std::size_t bytes = 0;      // the hierarchy in memory (the file is 64 bytes more)
  std::uint64_t fingerprint = 0;
};

class RouteIndex {
 public:
  // Builds the index of the moves the robot (`profile`, with the motion table `motion` if not
  // null) has on `map`, without closures, blockages or hazards: the graph every compile on that
  // map and robot starts from. Errors: a move of 49 days or more (kInvalidArgument); stopped by
  // `stop` (kCancelled or kSearchLimit). Runtime: seconds at 100,000 manholes (docs/benchmarks.md).
  static Result<RouteIndex> build(const SewerMap& map, const RobotProfile& profile,
                                  std::shared_ptr<const PassageMotionTable> motion,
                                  const StopCondition& stop = {});

  // Reads an index from the bytes of a file (docs/formats/route-index.md). Every count is checked
  // against the length before anything is allocated, and every edge, rank and shortcut against
  // the others, so no file can make a query crash; a file that is truncated, of another version
  // or not an index is refused (kParse, or kUnsupportedFormat for another version) with a message
  // naming `file_name` and what is wrong.
  static Result<RouteIndex> read(std::string_view bytes, const std::string& file_name);
  // The same, from a file (kIo if it cannot be read).
  static Result<RouteIndex> load(const std::filesystem::path& path);

  // The file's bytes (read() gives the same index back).
  std::string bytes() const;
  // Writes the file atomically (output_file.h); kIo naming the file.
  Result<void> save(const std::filesystem::path& path) const;

  const RouteIndexStatistics& statistics() const;
  std::uint64_t fingerprint() const { return statistics().fingerprint; }
  // The file it was read from (empty if built in this process), for messages.
  const std::string& source() const;

  struct Impl;
  // Private to domain (the compile takes the hierarchy from it).
  const Impl& impl() const { return *impl_; }

 private:
  explicit RouteIndex(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}
  // Shared: copies of an index (the CLI's, each CompileCache's and the cores') use one hierarchy
  // of tens of megabytes at a million manholes.
  std::shared_ptr<const Impl> impl_;
};

// Where a map's index is kept: beside it, "ais.json" -> "ais.route-index.bin" (as the motion
// table's "ais.motion.json").
std::filesystem::path default_route_index_path(const std::filesystem::path& map_path);

// The fingerprint as 16 hex digits, for messages.
std::string fingerprint_hex(std::uint64_t fingerprint);

}  // namespace sewerplan::domain
