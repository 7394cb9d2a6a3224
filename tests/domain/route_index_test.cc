// SPDX-License-Identifier: MIT
// Issue 35: the routing index made beforehand (route_index.h): its file read back as written, a
// compile on a cache given a loaded index the same as one without, a stale index refused, and
// every kind of broken file refused with what is wrong with it.
#include "sewerplan/domain/route_index.h"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/domain/compile.h"
#include "sewerplan/domain/mission_generator.h"

#include "route_index_internal.h"
#include "support/scrambled_network.h"
#include "support/task_compare.h"

namespace sewerplan::domain {
namespace {

using detail::Node;

std::filesystem::path temp_file(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("sewerplan_route_index_" +
          std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" + name);
}

TEST(RouteIndexIssue35, ReadsBackTheIndexItWroteWithTheSameDistancesAndWays) {
  const SewerMap map = *bench::generate_scrambled_network({.manholes = 300, .seed = 4});
  const RobotProfile profile = *builtin_profile("makro-1.1");
  const Result<RouteIndex> built = RouteIndex::build(map, profile, nullptr);
  ASSERT_TRUE(built.has_value()) << built.error().message;
  EXPECT_GT(built->statistics().shortcuts, 0U);
  const std::filesystem::path path = temp_file("round_trip.bin");
  ASSERT_TRUE(built->save(path).has_value());
  const Result<RouteIndex> loaded = RouteIndex::load(path);
  std::filesystem::remove(path);
  ASSERT_TRUE(loaded.has_value()) << loaded.error().message;
  EXPECT_EQ(loaded->source(), path.string());
  EXPECT_EQ(loaded->bytes(), built->bytes());
  EXPECT_EQ(loaded->bytes().size(), built->statistics().bytes - 4 * built->statistics().nodes + 64)
      << "the file has the arrays but the ranks' inverse, and the header";
  const RouteIndexStatistics& a = built->statistics();
  const RouteIndexStatistics& b = loaded->statistics();
  EXPECT_EQ(a.fingerprint, b.fingerprint);
  EXPECT_EQ(a.nodes, b.nodes);
  EXPECT_EQ(a.moves, b.moves);
  EXPECT_EQ(a.shortcuts, b.shortcuts);
  EXPECT_EQ(a.edges, b.edges);
  EXPECT_EQ(a.bytes, b.bytes);
  detail::ChQuery from_built(*built->impl().hierarchy);
  detail::ChQuery from_loaded(*loaded->impl().hierarchy);
  std::vector<Node> way_built;
  std::vector<Node> way_loaded;
  std::size_t found = 0;
  const auto n = static_cast<Node>(a.nodes);
  for (Node s = 0; s < n; s += 97) {
    for (Node t = 5; t < n; t += 89) {
      bool unique_built = false;
      bool unique_loaded = false;
      const Cost d = from_built.path(s, t, way_built, &unique_built);
      EXPECT_EQ(from_loaded.path(s, t, way_loaded, &unique_loaded), d);
      EXPECT_EQ(way_loaded, way_built);
      EXPECT_EQ(unique_loaded, unique_built);
      found += d != kInfiniteCost ? 1 : 0;
    }
  }
  EXPECT_GT(found, 10U);
}

// The tasks are the same, action for action and route for route.
using testing::expect_identical_task;

// A compile on a cache given the index saved and loaded takes its routes from it from the first
// compile on (no build, whatever the policy), and gives the task compiled without one; so do
// the replans after a blockage and a closure.
TEST(RouteIndexIssue35, CompilesFromALoadedIndexAsWithoutOne) {
  const SewerMap map = *bench::generate_scrambled_network({.manholes = 400, .seed = 5});
  Mission mission = *bench::scrambled_mission(map, 8, 3);
  const Result<RouteIndex> built = RouteIndex::build(map, mission.profile, nullptr);
  ASSERT_TRUE(built.has_value()) << built.error().message;
  const std::filesystem::path path = temp_file("compile.bin");
  ASSERT_TRUE(built->save(path).has_value());
  const Result<RouteIndex> loaded = RouteIndex::load(path);
  std::filesystem::remove(path);
  ASSERT_TRUE(loaded.has_value()) << loaded.error().message;
  CompileCache cache(CompileCache::RoutingIndex::kNever);
  const Result<void> used = cache.use_route_index(*loaded, map, mission.profile, nullptr);
  ASSERT_TRUE(used.has_value()) << used.error().message;
  MissionProgress progress = initial_progress(mission, map);
  std::size_t from_index = 0;
  for (int step = 0; step < 3; ++step) {
    SCOPED_TRACE("step " + std::to_string(step));
    if (step == 1) mission.blockages.push_back({PipeId{7}, map.pipe(PipeId{7}).length_m / 2});
    if (step == 2) mission.closed_pipes.push_back(PipeId{11});
    const auto with =
        compile_sewer_task(map, mission, progress, {.select_goals = true, .cache = &cache});
    const auto without = compile_sewer_task(map, mission, progress, {.select_goals = true});
    ASSERT_TRUE(with.has_value()) << with.error().message;
    ASSERT_TRUE(without.has_value()) << without.error().message;
    expect_identical_task(*with, *without);
    if (step == 0) {
      EXPECT_GT(with->statistics().index_rows, 0U) << "the first compile takes rows from it";
      EXPECT_LT(with->statistics().route_searches, without->statistics().route_searches);
    }
    from_index += with->statistics().index_rows;
    EXPECT_EQ(without->statistics().index_rows, 0U);
  }
  EXPECT_GT(from_index, 0U);
}

// An index is used only on the moves it was built over: another robot, another map, another
// motion table are refused, naming the file and both fingerprints.
TEST(RouteIndexIssue35, RefusesAStaleIndex) {
  const SewerMap map =
      *generate_network({.manholes = 200, .seed = 3, .topology = Topology::kMeshed});
  const RobotProfile makro = *builtin_profile("makro-1.1");
  const RobotProfile plus = *builtin_profile("makro-plus");
  const Result<RouteIndex> built = RouteIndex::build(map, makro, nullptr);
  ASSERT_TRUE(built.has_value()) << built.error().message;
  const Result<RouteIndex> index = RouteIndex::read(built->bytes(), "city.route-index.bin");
  ASSERT_TRUE(index.has_value()) << index.error().message;
  CompileCache cache;
  EXPECT_TRUE(cache.use_route_index(*index, map, makro, nullptr).has_value());
  const Result<void> robot = cache.use_route_index(*index, map, plus, nullptr);
  ASSERT_FALSE(robot.has_value());
  EXPECT_EQ(robot.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(robot.error().message.find("the routing index city.route-index.bin is stale"),
            std::string::npos)
      << robot.error().message;
  EXPECT_NE(robot.error().message.find(fingerprint_hex(index->fingerprint())), std::string::npos);
  const SewerMap other =
      *generate_network({.manholes = 200, .seed = 4, .topology = Topology::kMeshed});
  EXPECT_FALSE(cache.use_route_index(*index, other, makro, nullptr).has_value());
  // A motion table that gives one passage a planned duration changes the moves' costs too.
  std::vector<PassageMotion> planned;
  for (ManholeId m : map.manhole_ids()) {
    if (map.manhole(m).slot_count < 2) continue;
    planned.push_back({.manhole = m,
                       .from = SlotIndex{0},
                       .to = SlotIndex{1},
                       .feasible = true,
                       .duration_s = 1234.5});
    break;
  }
  ASSERT_EQ(planned.size(), 1U);
  const auto motion = std::make_shared<const PassageMotionTable>("", "", std::move(planned));
  EXPECT_FALSE(cache.use_route_index(*index, map, makro, motion).has_value());
}

// ---- Broken files -------------------------------------------------------------------------

std::uint32_t u32(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i)
    v |= std::uint32_t{static_cast<unsigned char>(b[at + i])} << (8 * i);
  return v;
}
void set_u32(std::string& b, std::size_t at, std::uint64_t v) {
  for (std::size_t i = 0; i < 4; ++i) b[at + i] = static_cast<char>((v >> (8 * i)) & 0xffU);
}
void set_u64(std::string& b, std::size_t at, std::uint64_t v) {
  for (std::size_t i = 0; i < 8; ++i) b[at + i] = static_cast<char>((v >> (8 * i)) & 0xffU);
}
// The checksum made right again, so that the structural checks behind it are reached.
void reseal(std::string& b) {
  set_u64(b, 56, detail::file_checksum(std::string_view(b).substr(64)));
}

// Where the arrays of a file lie (docs/formats/route-index.md).
struct Layout {
  std::size_t n, up, down, up_begin, up_edges, down_begin, down_edges;
  explicit Layout(const std::string& b)
      : n(u32(b, 24)),
        up(u32(b, 40)),
        down(u32(b, 48)),
        up_begin(64 + 4 * n),
        up_edges(up_begin + 4 * (n + 1)),
        down_begin(up_edges + 12 * up),
        down_edges(down_begin + 4 * (n + 1)) {}
  // The first up edge (its offset, and the rank it is stored at) that `pick` accepts.
  std::pair<std::size_t, std::uint32_t> up_edge(
      const std::string& b, const std::function<bool(std::size_t)>& pick) const {
    for (std::uint32_t u = 0; u < n; ++u) {
      for (std::uint32_t e = u32(b, up_begin + 4 * u); e < u32(b, up_begin + 4 * (u + 1)); ++e) {
        if (pick(up_edges + 12 * e)) return {up_edges + 12 * e, u};
      }
    }
    ADD_FAILURE() << "no such edge";
    return {0, 0};
  }
};

TEST(RouteIndexIssue35, RefusesEveryKindOfBrokenFileSayingWhatIsWrong) {
  const SewerMap map =
      *generate_network({.manholes = 60, .seed = 2, .topology = Topology::kMeshed});
  const Result<RouteIndex> built = RouteIndex::build(map, *builtin_profile("makro-1.1"), nullptr);
  ASSERT_TRUE(built.has_value()) << built.error().message;
  const std::string good = built->bytes();
  const Layout at(good);
  ASSERT_TRUE(RouteIndex::read(good, "x.bin").has_value());
  const auto shortcut = [&](const std::string& b) {
    return at.up_edge(b,
                      [&](std::size_t e) { return (u32(b, e + 8) & 0x7fffffffU) != 0x7fffffffU; });
  };
  struct Case {
    std::string what;
    std::function<void(std::string&)> spoil;
    ErrorCode code;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"empty", [](std::string& b) { b.clear(); }, ErrorCode::kParse,
       "truncated: 0 bytes, where the header alone has 64"},
      {"half a header", [](std::string& b) { b.resize(30); }, ErrorCode::kParse, "truncated: 30"},
      {"another format", [](std::string& b) { b[0] = '{'; }, ErrorCode::kParse,
       "not a sewerplan routing index"},
      {"another version", [](std::string& b) { set_u32(b, 8, 1); }, ErrorCode::kUnsupportedFormat,
       "version 1 of the routing index; this sewerplan reads version 2: remake it with "
       "'sewerplan index build'"},
      {"other flags", [](std::string& b) { set_u32(b, 12, 0); }, ErrorCode::kParse, "flags 0"},
      {"a count larger than the file",
       [](std::string& b) { set_u64(b, 24, std::uint64_t{1} << 40); }, ErrorCode::kParse,
       "truncated or corrupt: its counts (1099511627776 nodes"},
      {"an edge count of 2^64 - 1", [](std::string& b) { set_u64(b, 40, ~std::uint64_t{0}); },
       ErrorCode::kParse, "truncated or corrupt"},
      {"the last byte cut", [](std::string& b) { b.pop_back(); }, ErrorCode::kParse, "truncated: "},
      {"a byte more", [](std::string& b) { b.push_back('\0'); }, ErrorCode::kParse,
       "trailing bytes: "},
      {"a flipped bit", [](std::string& b) { b[b.size() / 2] ^= 4; }, ErrorCode::kParse,
       "corrupt: its checksum does not match its contents"},
      {"a rank out of range",
       [&](std::string& b) {
         set_u32(b, 64, at.n);
         reseal(b);
       },
       ErrorCode::kParse, "node 0's rank " + std::to_string(at.n) + " is out of range"},
      {"two nodes of one rank",
       [&](std::string& b) {
         set_u32(b, 68, u32(b, 64));
         reseal(b);
       },
       ErrorCode::kParse, "node 1's rank " + std::to_string(u32(good, 64)) + " is another node's"},
      {"offsets falling",
       [&](std::string& b) {
         set_u32(b, at.up_begin + 4 * at.n, at.up + 1);
         reseal(b);
       },
       ErrorCode::kParse, "the up edges' offset " + std::to_string(at.n)},
      {"a head out of range",
       [&](std::string& b) {
         set_u32(b, at.up_edges, at.n);
         reseal(b);
       },
       ErrorCode::kParse, "up edge 0 (of rank "},
      {"an edge that does not climb",
       [&](std::string& b) {
         const auto [e, u] = at.up_edge(b, [](std::size_t) { return true; });
         set_u32(b, e, u);
         reseal(b);
       },
       ErrorCode::kParse, "is not above its own"},
      {"two edges of a node out of order",
       [&](std::string& b) {
         // The first node with two up edges: its second edge's head set to its first's.
         for (std::uint32_t u = 0; u < at.n; ++u) {
           const std::uint32_t first = u32(b, at.up_begin + 4 * u);
           if (u32(b, at.up_begin + 4 * (u + 1)) < first + 2) continue;
           set_u32(b, at.up_edges + 12 * (first + 1), u32(b, at.up_edges + 12 * first));
           break;
         }
         reseal(b);
       },
       ErrorCode::kParse, "a node's edges are sorted by head, each once"},
      {"a middle above the edge",
       [&](std::string& b) {
         const auto [e, u] = shortcut(b);
         set_u32(b, e + 8, u);
         reseal(b);
       },
       ErrorCode::kParse, "is not below its own"},
      {"a cost of 2^32 - 1",
       [&](std::string& b) {
         set_u32(b, at.up_edges + 4, 0xffffffffU);
         reseal(b);
       },
       ErrorCode::kParse, "cost 2^32 - 1 ms"},
      {"a shortcut costing more than its halves",
       [&](std::string& b) {
         const auto [e, u] = shortcut(b);
         set_u32(b, e + 4, u32(b, e + 4) + 1);
         reseal(b);
       },
       ErrorCode::kParse, "where its halves cost"},
      {"a shortcut without its halves",
       [&](std::string& b) {
         // Its middle the lowest node, which has no edge to this one's ends (or not both).
         const auto [e, u] = shortcut(b);
         const std::uint32_t head = u32(b, e);
         for (std::uint32_t m = 0; m < u; ++m) {
           bool to_u = false;
           bool to_head = false;
           for (std::uint32_t d = u32(b, at.down_begin + 4 * m);
                d < u32(b, at.down_begin + 4 * (m + 1)); ++d) {
             to_u = to_u || u32(b, at.down_edges + 12 * d) == u;
           }
           for (std::uint32_t x = u32(b, at.up_begin + 4 * m);
                x < u32(b, at.up_begin + 4 * (m + 1)); ++x) {
             to_head = to_head || u32(b, at.up_edges + 12 * x) == head;
           }
           if (!to_u || !to_head) {
             set_u32(b, e + 8, m);
             break;
           }
         }
         reseal(b);
       },
       ErrorCode::kParse, "which has no edge to rank"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    std::string bytes = good;
    c.spoil(bytes);
    const Result<RouteIndex> read = RouteIndex::read(bytes, "x.route-index.bin");
    ASSERT_FALSE(read.has_value());
    EXPECT_EQ(read.error().code, c.code);
    EXPECT_EQ(read.error().message.rfind("x.route-index.bin: ", 0), 0U) << read.error().message;
    EXPECT_NE(read.error().message.find(c.message), std::string::npos) << read.error().message;
  }
  const Result<RouteIndex> missing = RouteIndex::load(temp_file("missing.bin"));
  ASSERT_FALSE(missing.has_value());
  EXPECT_EQ(missing.error().code, ErrorCode::kIo);
  EXPECT_NE(missing.error().message.find("missing.bin"), std::string::npos);
}

TEST(RouteIndexIssue35, KeepsTheIndexBesideTheMap) {
  EXPECT_EQ(default_route_index_path("data/ais.json"), "data/ais.route-index.bin");
  EXPECT_EQ(fingerprint_hex(0x12ab), "00000000000012ab");
}

}  // namespace
}  // namespace sewerplan::domain
