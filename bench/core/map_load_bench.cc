// SPDX-License-Identifier: MIT
// Loading maps: the native JSON format and the ASCII database, against the JSON parser alone.
//
// Issue #2's figure: a 100,000-manhole JSON map loads in under 1 s and takes under 200 bytes per
// manhole plus pipe in memory (counter bytes_per_object = SewerMap::memory_bytes() / (manholes +
// pipes)). The input is generated once per size (meshed, seed 1) and held in memory, so the
// figures exclude disk I/O. BM_MapJsonRead takes the reader's fast path (one pass, no document
// tree: core/src/map_json_fast.h); BM_MapJsonReadDocument, its baseline, the simdjson document
// reader that reads (and reports) everything the fast path leaves to it.
#include <map>
#include <sstream>

#include <benchmark/benchmark.h>
#include <nlohmann/json.hpp>

#include "sewerplan/core/generator.h"
#include "sewerplan/core/map_ascii.h"
#include "sewerplan/core/map_json.h"

#include "map_json_fast.h"

namespace sewerplan {
namespace {

struct Texts {
  std::string json;
  std::string ascii;
};

const Texts& texts_for(std::size_t manholes) {
  static std::map<std::size_t, Texts> cache;
  auto it = cache.find(manholes);
  if (it != cache.end()) return it->second;
  Result<SewerMap> map =
      generate_network({.manholes = manholes, .seed = 1, .topology = Topology::kMeshed});
  Texts t;
  std::ostringstream json, ascii;
  write_map_json(*map, json);
  (void)write_map_ascii(*map, ascii);
  t.json = json.str();
  t.ascii = ascii.str();
  return cache.emplace(manholes, std::move(t)).first->second;
}

void report(benchmark::State& state, const SewerMap& map, std::size_t bytes) {
  const auto objects = static_cast<double>(map.manhole_count() + map.pipe_count());
  state.counters["bytes_per_object"] = static_cast<double>(map.memory_bytes()) / objects;
  state.counters["file_MB"] = static_cast<double>(bytes) / 1e6;
  state.counters["manholes_per_s"] = benchmark::Counter(
      static_cast<double>(map.manhole_count()), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_MapJsonRead(benchmark::State& state) {
  const std::string& text = texts_for(static_cast<std::size_t>(state.range(0))).json;
  SewerMap last;
  for (auto _ : state) {
    Diagnostics d;
    Result<SewerMap> map = read_map_json(text, "bench.json", d);
    if (!map.has_value()) state.SkipWithError(map.error().message.c_str());
    last = std::move(*map);
  }
  report(state, last, text.size());
}

void BM_MapJsonReadDocument(benchmark::State& state) {
  const std::string& text = texts_for(static_cast<std::size_t>(state.range(0))).json;
  SewerMap last;
  for (auto _ : state) {
    Diagnostics d;
    Result<SewerMap> map = detail::read_map_json_document(text, "bench.json", d);
    if (!map.has_value()) state.SkipWithError(map.error().message.c_str());
    last = std::move(*map);
  }
  report(state, last, text.size());
}

void BM_MapAsciiRead(benchmark::State& state) {
  const std::string& text = texts_for(static_cast<std::size_t>(state.range(0))).ascii;
  SewerMap last;
  for (auto _ : state) {
    Diagnostics d;
    Result<SewerMap> map = read_map_ascii(text, "bench.sewer", d);
    if (!map.has_value()) state.SkipWithError(map.error().message.c_str());
    last = std::move(*map);
  }
  report(state, last, text.size());
}

// Baseline: nlohmann::json's parser alone, building its document tree and nothing else.
void BM_NlohmannParseOnly(benchmark::State& state) {
  const std::string& text = texts_for(static_cast<std::size_t>(state.range(0))).json;
  for (auto _ : state) {
    nlohmann::json doc = nlohmann::json::parse(text);
    benchmark::DoNotOptimize(doc);
  }
}

void BM_MapJsonWrite(benchmark::State& state) {
  const std::string& text = texts_for(static_cast<std::size_t>(state.range(0))).json;
  Diagnostics d;
  Result<SewerMap> map = read_map_json(text, "bench.json", d);
  for (auto _ : state) {
    std::ostringstream out;
    write_map_json(*map, out);
    benchmark::DoNotOptimize(out);
  }
}

BENCHMARK(BM_MapJsonRead)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MapJsonReadDocument)
    ->Arg(1000)
    ->Arg(10000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MapAsciiRead)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NlohmannParseOnly)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MapJsonWrite)->Arg(100000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sewerplan
