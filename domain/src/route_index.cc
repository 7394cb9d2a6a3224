// SPDX-License-Identifier: MIT
// RouteIndex (route_index.h): built over the compile's graph, written and read as the binary file
// of docs/formats/route-index.md, every byte of which the reader checks.
#include "sewerplan/domain/route_index.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <span>
#include <sstream>
#include <system_error>
#include <tuple>
#include <vector>

#include "sewerplan/core/mapped_file.h"
#include "sewerplan/core/output_file.h"

#include "route_index_internal.h"

namespace sewerplan::domain {

namespace detail {

namespace {

constexpr std::array<char, 8> kMagic = {'S', 'P', 'R', 'I', 'D', 'X', '\r', '\n'};
constexpr std::uint32_t kVersion = 2;   // 2: each node's edges sorted by head
constexpr std::uint32_t kKeepTies = 1;  // flags bit 0: built with ChOptions::keep_ties
constexpr std::size_t kHeaderBytes = 64;
constexpr std::size_t kEdgeBytes = 12;
// Deeper shortcuts are refused: unpacking one recurses once per level. The hierarchies of our
// and the scrambled networks at 100,000 manholes nest theirs at most 19 deep (a throwaway
// counter, 2026-12-07); a byte per edge holds the depth while the reader checks it.
constexpr std::uint32_t kMaxShortcutDepth = 255;
// Files of this size and more are mapped rather than read into a buffer (RouteIndex::load).
constexpr std::size_t kMappedBytes = std::size_t{1} << 20;

// FNV-1a, 64 bits (Fowler, Noll and Vo), over values as their little-endian bytes: the same on
// every platform and in every run (std::hash is neither).
class Fnv {
 public:
  void add(std::uint64_t value, int bytes) {
    for (int i = 0; i < bytes; ++i) {
      hash_ ^= (value >> (8 * i)) & 0xffU;
      hash_ *= 1099511628211ULL;
    }
  }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 14695981039346656037ULL;
};

void put(std::string& out, std::uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xffU));
}

std::uint64_t get(std::string_view in, std::size_t at, int bytes) {
  std::uint64_t value = 0;
  for (int i = 0; i < bytes; ++i) {
    value |= std::uint64_t{static_cast<unsigned char>(in[at + static_cast<std::size_t>(i)])}
             << (8 * i);
  }
  return value;
}

}  // namespace

// Eight independent lanes run several times as fast as one FNV-1a over 270 MB (a multiply's
// latency per byte), where the one took a seventh of the reading time at a million manholes.
std::uint64_t file_checksum(std::string_view bytes) {
  constexpr std::uint64_t kPrime = 1099511628211ULL;
  std::array<std::uint64_t, 8> lane;
  lane.fill(14695981039346656037ULL);
  std::size_t i = 0;
  for (; i + 8 <= bytes.size(); i += 8) {
    for (std::size_t k = 0; k < 8; ++k) {
      lane[k] = (lane[k] ^ static_cast<unsigned char>(bytes[i + k])) * kPrime;
    }
  }
  for (std::size_t k = 0; i + k < bytes.size(); ++k) {
    lane[k] = (lane[k] ^ static_cast<unsigned char>(bytes[i + k])) * kPrime;
  }
  Fnv all;
  for (std::uint64_t h : lane) all.add(h, 8);
  return all.value();
}

std::uint64_t adjacency_fingerprint(const GraphCore& core) {
  Fnv fnv;
  fnv.add(core.adjacency_begin.size(), 8);
  fnv.add(core.adjacency_to.size(), 8);
  for (std::uint32_t b : core.adjacency_begin) fnv.add(b, 4);
  for (Node n : core.adjacency_to) fnv.add(n, 4);
  for (Cost c : core.adjacency_cost) fnv.add(static_cast<std::uint64_t>(c), 8);
  return fnv.value();
}

// The file format's access to the hierarchy's arrays (a friend of ContractionHierarchy).
struct ChFile {
  using Edge = ContractionHierarchy::Edge;

  static std::string write(const ContractionHierarchy& ch, std::uint64_t fingerprint) {
    std::string body;
    body.reserve(ch.statistics_.bytes);
    for (std::uint32_t r : ch.rank_) put(body, r, 4);
    const auto edges = [&](const std::vector<std::uint32_t>& begin, const std::vector<Edge>& e) {
      for (std::uint32_t b : begin) put(body, b, 4);
      for (const Edge& edge : e) {
        put(body, edge.head, 4);
        put(body, edge.cost, 4);
        put(body, edge.middle_tied, 4);
      }
    };
    edges(ch.up_begin_, ch.up_);
    edges(ch.down_begin_, ch.down_);
    std::string out(kMagic.begin(), kMagic.end());
    put(out, kVersion, 4);
    put(out, kKeepTies, 4);
    put(out, fingerprint, 8);
    put(out, ch.rank_.size(), 8);
    put(out, ch.statistics_.moves, 8);
    put(out, ch.up_.size(), 8);
    put(out, ch.down_.size(), 8);
    put(out, file_checksum(body), 8);
    return out + body;
  }

  // The hierarchy in `bytes`, or what is wrong with it (the message without the file's name).
  static Result<ContractionHierarchy> read(std::string_view bytes, std::uint64_t* fingerprint) {
    const auto parse_error = [](std::string message) {
      return Error{ErrorCode::kParse, std::move(message)};
    };
    if (bytes.size() < kHeaderBytes) {
      return parse_error("truncated: " + std::to_string(bytes.size()) +
                         " bytes, where the header alone has 64");
    }
    if (!std::equal(kMagic.begin(), kMagic.end(), bytes.begin())) {
      return parse_error("not a sewerplan routing index (it does not begin with \"SPRIDX\")");
    }
    const std::uint64_t version = get(bytes, 8, 4);
    if (version != kVersion) {
      return Error{ErrorCode::kUnsupportedFormat, "version " + std::to_string(version) +
                                                      " of the routing index; this sewerplan " +
                                                      "reads version " + std::to_string(kVersion) +
                                                      ": remake it with 'sewerplan index build'"};
    }
    if (get(bytes, 12, 4) != kKeepTies) {
      return parse_error("flags " + std::to_string(get(bytes, 12, 4)) + ": a version " +
                         std::to_string(kVersion) + " index has flags 1 (built keeping every " +
                         "shortest way)");
    }
    *fingerprint = get(bytes, 16, 8);
    const std::uint64_t n = get(bytes, 24, 8);
    const std::uint64_t moves = get(bytes, 32, 8);
    const std::uint64_t up = get(bytes, 40, 8);
    const std::uint64_t down = get(bytes, 48, 8);
    // Each count at most the file's length before any arithmetic: no sum below overflows.
    const std::uint64_t length = bytes.size();
    if (n >= ContractionHierarchy::kNoMiddle || n > length || up > length || down > length ||
        moves > length) {
      return parse_error("truncated or corrupt: its counts (" + std::to_string(n) + " nodes, " +
                         std::to_string(up) + " up and " + std::to_string(down) + " down edges, " +
                         std::to_string(moves) + " moves) do not fit in its " +
                         std::to_string(length) + " bytes");
    }
    const std::uint64_t expected =
        kHeaderBytes + 4 * n + 2 * 4 * (n + 1) + kEdgeBytes * (up + down);
    if (expected != length) {
      return parse_error(std::string(length < expected ? "truncated: " : "trailing bytes: ") +
                         std::to_string(length) + " bytes, where its counts (" + std::to_string(n) +
                         " nodes, " + std::to_string(up + down) + " edges) make " +
                         std::to_string(expected));
    }
    if (file_checksum(bytes.substr(kHeaderBytes)) != get(bytes, 56, 8)) {
      return parse_error("corrupt: its checksum does not match its contents");
    }
    ContractionHierarchy ch;
    std::size_t at = kHeaderBytes;
    ch.rank_.resize(n);
    ch.node_.assign(n, ContractionHierarchy::kNoMiddle);
    for (std::uint32_t v = 0; v < n; ++v, at += 4) {
      const auto r = static_cast<std::uint32_t>(get(bytes, at, 4));
      if (r >= n || ch.node_[r] != ContractionHierarchy::kNoMiddle) {
        return parse_error("node " + std::to_string(v) + "'s rank " + std::to_string(r) +
                           (r >= n ? " is out of range" : " is another node's too") +
                           ": the ranks must be a permutation of 0.." + std::to_string(n) + "-1");
      }
      ch.rank_[v] = r;
      ch.node_[r] = v;
    }
    for (auto [begin, edges, count, side] :
         {std::tuple{&ch.up_begin_, &ch.up_, up, "up"},
          std::tuple{&ch.down_begin_, &ch.down_, down, "down"}}) {
      if (auto r = read_edges(bytes, at, n, count, side, *begin, *edges); !r.has_value()) {
        return r.error();
      }
    }
    if (auto r = check_shortcuts(ch); !r.has_value()) return r.error();
    ChStatistics& s = ch.statistics_;
    s.nodes = n;
    s.moves = moves;
    s.up_edges = up;
    s.down_edges = down;
    for (const auto* edges : {&ch.up_, &ch.down_}) {
      for (const Edge& e : *edges) s.shortcuts += e.middle() != ContractionHierarchy::kNoMiddle;
    }
    s.bytes = (ch.rank_.size() + ch.node_.size() + ch.up_begin_.size() + ch.down_begin_.size()) *
                  sizeof(std::uint32_t) +
              (ch.up_.size() + ch.down_.size()) * sizeof(Edge);
    return ch;
  }

 private:
  // One side's offsets (n + 1, from 0 to `count`, never falling) and edges (each to a higher
  // node, its middle none or a lower node than its own); `at` moves past them.
  static Result<void> read_edges(std::string_view bytes, std::size_t& at, std::uint64_t n,
                                 std::uint64_t count, const char* side,
                                 std::vector<std::uint32_t>& begin, std::vector<Edge>& edges) {
    begin.resize(n + 1);
    for (std::size_t u = 0; u <= n; ++u, at += 4) {
      begin[u] = static_cast<std::uint32_t>(get(bytes, at, 4));
      const bool bad = (u == 0 && begin[u] != 0) || (u > 0 && begin[u] < begin[u - 1]) ||
                       begin[u] > count || (u == n && begin[u] != count);
      if (bad) {
        return Error{ErrorCode::kParse, std::string("the ") + side + " edges' offset " +
                                            std::to_string(u) + " (" + std::to_string(begin[u]) +
                                            ") breaks their order: from 0, never falling, to " +
                                            std::to_string(count)};
      }
    }
    edges.resize(count);
    std::uint32_t u = 0;
    for (std::uint32_t e = 0; e < count; ++e, at += kEdgeBytes) {
      while (begin[u + 1] <= e) ++u;
      Edge& edge = edges[e];
      edge.head = static_cast<std::uint32_t>(get(bytes, at, 4));
      const std::uint64_t cost = get(bytes, at + 4, 4);
      edge.cost = static_cast<std::uint32_t>(cost);
      edge.middle_tied = static_cast<std::uint32_t>(get(bytes, at + 8, 4));
      // Made only for a message (a string per edge took two thirds of the reading time).
      const auto where = [&] {
        return std::string(side) + " edge " + std::to_string(e) + " (of rank " + std::to_string(u) +
               ")";
      };
      if (edge.head <= u || edge.head >= n) {
        return Error{ErrorCode::kParse, where() + ": head rank " + std::to_string(edge.head) +
                                            " is not above its own and below " + std::to_string(n)};
      }
      if (e > begin[u] && edge.head <= edges[e - 1].head) {
        return Error{ErrorCode::kParse, where() + ": head rank " + std::to_string(edge.head) +
                                            " is not above the previous edge's (" +
                                            std::to_string(edges[e - 1].head) +
                                            "): a node's edges are sorted by head, each once"};
      }
      if (cost == 0xffffffffU) {
        return Error{ErrorCode::kParse, where() + ": cost 2^32 - 1 ms, more than any edge has"};
      }
      if (edge.middle() != ContractionHierarchy::kNoMiddle && edge.middle() >= u) {
        return Error{ErrorCode::kParse, where() + ": middle rank " + std::to_string(edge.middle()) +
                                            " is not below its own"};
      }
    }
    return Result<void>{};
  }

  // The edge to `head` among the side's edges at `tail`; null if none.
  static const Edge* find(const std::vector<std::uint32_t>& begin, const std::vector<Edge>& edges,
                          std::uint32_t tail, std::uint32_t head, std::size_t* index) {
    const auto first = edges.begin() + begin[tail];
    const auto last = edges.begin() + begin[tail + 1];
    const auto it = std::lower_bound(first, last, head,
                                     [](const Edge& x, std::uint32_t h) { return x.head < h; });
    if (it == last || it->head != head) return nullptr;
    *index = static_cast<std::size_t>(it - edges.begin());
    return &*it;
  }

  // Every shortcut's two halves exist (ContractionHierarchy::unpack), cost as much as it together,
  // unpack to at most n - 1 moves (a shortest way visits a node once) and nest at most
  // kMaxShortcutDepth deep. Ranks ascending: a shortcut's halves are at its middle, below it.
  static Result<void> check_shortcuts(const ContractionHierarchy& ch) {
    const std::size_t n = ch.rank_.size();
    std::vector<std::uint32_t> up_moves(ch.up_.size(), 1);
    std::vector<std::uint32_t> down_moves(ch.down_.size(), 1);
    std::vector<std::uint8_t> up_depth(ch.up_.size(), 0);
    std::vector<std::uint8_t> down_depth(ch.down_.size(), 0);
    for (std::uint32_t u = 0; u < n; ++u) {
      for (bool is_up : {true, false}) {
        const auto& begin = is_up ? ch.up_begin_ : ch.down_begin_;
        const auto& edges = is_up ? ch.up_ : ch.down_;
        for (std::uint32_t e = begin[u]; e < begin[u + 1]; ++e) {
          const Edge& edge = edges[e];
          const std::uint32_t m = edge.middle();
          if (m == ContractionHierarchy::kNoMiddle) continue;
          // unpack(tail, head, m): tail -> m is a down edge at m, m -> head an up edge at m. An up
          // edge at u goes u -> head; a down edge at u comes head -> u.
          const std::uint32_t tail = is_up ? u : edge.head;
          const std::uint32_t head = is_up ? edge.head : u;
          std::size_t first = 0;
          std::size_t second = 0;
          const Edge* a = find(ch.down_begin_, ch.down_, m, tail, &first);
          const Edge* b = find(ch.up_begin_, ch.up_, m, head, &second);
          const auto where = [&] {
            return std::string(is_up ? "up" : "down") + " edge " + std::to_string(e) +
                   " (of rank " + std::to_string(u) + ")";
          };
          if (a == nullptr || b == nullptr) {
            return Error{ErrorCode::kParse, where() + ": a shortcut by rank " + std::to_string(m) +
                                                ", which has no edge to rank " +
                                                std::to_string(a == nullptr ? tail : head)};
          }
          if (std::uint64_t{a->cost} + b->cost != edge.cost) {
            return Error{ErrorCode::kParse,
                         where() + ": a shortcut costing " + std::to_string(edge.cost) +
                             " ms, where its halves cost " + std::to_string(a->cost) + " + " +
                             std::to_string(b->cost)};
          }
          const std::uint64_t moves = std::uint64_t{down_moves[first]} + up_moves[second];
          const std::uint32_t depth =
              std::uint32_t{std::max(down_depth[first], up_depth[second])} + 1;
          if (moves >= n || depth > kMaxShortcutDepth) {
            return Error{ErrorCode::kParse, where() + ": a shortcut of " + std::to_string(moves) +
                                                " moves nested " + std::to_string(depth) +
                                                " deep, more than a way on " + std::to_string(n) +
                                                " nodes has (or than " +
                                                std::to_string(kMaxShortcutDepth) + " levels)"};
          }
          (is_up ? up_moves : down_moves)[e] = static_cast<std::uint32_t>(moves);
          (is_up ? up_depth : down_depth)[e] = static_cast<std::uint8_t>(depth);
        }
      }
    }
    return Result<void>{};
  }
};

}  // namespace detail

void RouteIndex::Impl::hold(detail::ContractionHierarchy ch) {
  hierarchy = std::make_shared<const detail::ContractionHierarchy>(std::move(ch));
  const detail::ChStatistics& s = hierarchy->statistics();
  statistics.nodes = s.nodes;
  statistics.moves = s.moves;
  statistics.shortcuts = s.shortcuts;
  statistics.edges = s.up_edges + s.down_edges;
  statistics.bytes = s.bytes;
}

std::shared_ptr<detail::GraphCore> detail::core_with_adjacency(
    std::shared_ptr<GraphCore> core, const SewerMap& map, const RobotProfile& profile,
    std::shared_ptr<const PassageMotionTable> motion, const StopCondition& stop) {
  if (core == nullptr || !core->serves(map, profile, motion.get())) {
    core = std::make_shared<GraphCore>(map, profile, std::move(motion), &stop);
    if (!core->complete) return nullptr;
  }
  Mission plain;
  plain.profile = profile;
  plain.passage_motion = core->motion;
  PositionGraph graph(map, plain, core);
  if (!graph.build_adjacency(&stop)) return nullptr;
  return core;
}

Result<RouteIndex> RouteIndex::build(const SewerMap& map, const RobotProfile& profile,
                                     std::shared_ptr<const PassageMotionTable> motion,
                                     const StopCondition& stop) {
  const auto stopped = [&] {
    return stopped_error(stop.interrupted().value_or(SearchStatus::kCancelled),
                         "the routing index's build");
  };
  const auto core = detail::core_with_adjacency(nullptr, map, profile, std::move(motion), stop);
  if (core == nullptr) return stopped();
  auto built = detail::ContractionHierarchy::build(
      core->adjacency_begin, core->adjacency_to, core->adjacency_cost,
      {.keep_ties = true, .stop = stop.can_interrupt() ? &stop : nullptr});
  if (!built.has_value()) {
    if (built.error().code == ErrorCode::kCancelled) return stopped();
    return built.error();
  }
  auto impl = std::make_shared<Impl>();
  impl->statistics.fingerprint = detail::adjacency_fingerprint(*core);
  impl->hold(std::move(*built));
  return RouteIndex(std::move(impl));
}

Result<RouteIndex> RouteIndex::read(std::string_view bytes, const std::string& file_name) {
  auto impl = std::make_shared<Impl>();
  Result<detail::ContractionHierarchy> ch =
      detail::ChFile::read(bytes, &impl->statistics.fingerprint);
  if (!ch.has_value()) {
    return Error{ch.error().code, file_name + ": " + ch.error().message +
                                      " (remake it with 'sewerplan index build')"};
  }
  impl->hold(std::move(*ch));
  impl->source = file_name;
  return RouteIndex(std::move(impl));
}

Result<RouteIndex> RouteIndex::load(const std::filesystem::path& path) {
  const std::string name = path.string();
  // Read where the page cache holds it: a buffer of 270 MB at a million manholes was zeroed and
  // copied into, a sixth of `plan`'s time with the index there (docs/benchmarks.md).
  if (auto mapped = sewerplan::detail::MappedFile::open(path, detail::kMappedBytes)) {
    return read(mapped->text(), name);
  }
  const auto cannot = [&](const std::string& why) {
    return Error{ErrorCode::kIo, "cannot read " + name + ": " + why};
  };
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return cannot("it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) return cannot(std::error_code(errno, std::generic_category()).message());
  // The file's own length, not a count read from it, sizes the buffer.
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(0, std::ios::beg);
  if (size < 0 || !in) return cannot("its size cannot be read");
  std::string bytes(static_cast<std::size_t>(size), '\0');
  if (!in.read(bytes.data(), size)) return cannot("read error");
  return read(bytes, name);
}

std::string RouteIndex::bytes() const {
  return detail::ChFile::write(*impl_->hierarchy, impl_->statistics.fingerprint);
}

Result<void> RouteIndex::save(const std::filesystem::path& path) const {
  return write_text_file(path, bytes());
}

const RouteIndexStatistics& RouteIndex::statistics() const { return impl_->statistics; }
const std::string& RouteIndex::source() const { return impl_->source; }

std::filesystem::path default_route_index_path(const std::filesystem::path& map_path) {
  std::filesystem::path p = map_path;
  p.replace_extension(".route-index.bin");
  return p;
}

std::string fingerprint_hex(std::uint64_t fingerprint) {
  std::ostringstream out;
  out << std::hex << std::setw(16) << std::setfill('0') << fingerprint;
  return out.str();
}

}  // namespace sewerplan::domain
