// SPDX-License-Identifier: MIT
// Importing sewer databases: SWMM .inp and ISYBAU XML, against reading the same network in the
// native ASCII format (the baseline: the same network, no foreign-format work).
//
// Issue #6's figure: a 10,000-node SWMM file imports in under 200 ms. The file is written in
// memory from a generated network (tree, seed 1): one junction per manhole, one conduit per pipe
// with its end inverts as ELEVATION offsets, CIRCULAR cross-sections and coordinates, so the
// importer does all its work (units, offsets, azimuths, validation). The shared files
// (datasets/swmm, datasets/isybau) are read from disk once and imported from memory.
#include <map>
#include <sstream>

#include <benchmark/benchmark.h>

#include "sewerplan/core/generator.h"
#include "sewerplan/core/map_ascii.h"
#include "sewerplan/core/map_isybau.h"
#include "sewerplan/core/map_swmm.h"
#include "sewerplan/core/text_file.h"

namespace sewerplan {
namespace {

// `map` as a SWMM 5 input file in SI units, pipes with a blind end left out.
std::string as_swmm(const SewerMap& map) {
  std::ostringstream out;
  out.precision(17);
  out << "[TITLE]\ngenerated\n\n[OPTIONS]\nFLOW_UNITS CMS\nLINK_OFFSETS ELEVATION\n\n[JUNCTIONS]\n";
  for (const Manhole& m : map.manholes()) out << m.name << ' ' << m.position.z_m << " 3 0 0 0\n";
  std::ostringstream xsections;
  xsections.precision(17);
  out << "\n[CONDUITS]\n";
  for (PipeId p : map.pipe_ids()) {
    const Pipe& pipe = map.pipe(p);
    if (!pipe.ends[0].manhole || !pipe.ends[1].manhole) continue;
    const double in = map.slot(*pipe.ends[0].manhole, pipe.ends[0].slot).invert_z_m;
    const double out_z = map.slot(*pipe.ends[1].manhole, pipe.ends[1].slot).invert_z_m;
    out << pipe.name << ' ' << map.manhole(*pipe.ends[0].manhole).name << ' '
        << map.manhole(*pipe.ends[1].manhole).name << ' ' << pipe.length_m << " 0.013 " << in << ' '
        << out_z << " 0 0\n";
    xsections << pipe.name << " CIRCULAR " << pipe.diameter_m << " 0 0 0 1\n";
  }
  out << "\n[XSECTIONS]\n" << xsections.str() << "\n[COORDINATES]\n";
  for (const Manhole& m : map.manholes()) {
    out << m.name << ' ' << m.position.x_m << ' ' << m.position.y_m << '\n';
  }
  return out.str();
}

struct Texts {
  std::string swmm;
  std::string ascii;  // the SWMM import written back in the native ASCII format
};

const Texts& texts_for(std::size_t manholes) {
  static std::map<std::size_t, Texts> cache;
  auto it = cache.find(manholes);
  if (it != cache.end()) return it->second;
  Result<SewerMap> map = generate_network({.manholes = manholes, .seed = 1});
  Texts t;
  t.swmm = as_swmm(*map);
  Diagnostics d;
  Result<SewerMap> imported = read_map_swmm(t.swmm, "bench.inp", d);
  std::ostringstream ascii;
  if (imported.has_value()) (void)write_map_ascii(*imported, ascii);
  t.ascii = ascii.str();
  return cache.emplace(manholes, std::move(t)).first->second;
}

void report(benchmark::State& state, const SewerMap& map, std::size_t bytes) {
  state.counters["manholes"] = static_cast<double>(map.manhole_count());
  state.counters["file_MB"] = static_cast<double>(bytes) / 1e6;
}

void BM_SwmmImport(benchmark::State& state) {
  const std::string& text = texts_for(static_cast<std::size_t>(state.range(0))).swmm;
  SewerMap last;
  for (auto _ : state) {
    Diagnostics d;
    Result<SewerMap> map = read_map_swmm(text, "bench.inp", d);
    if (!map.has_value()) return state.SkipWithError(map.error().message.c_str());
    last = std::move(*map);
  }
  report(state, last, text.size());
}
BENCHMARK(BM_SwmmImport)->Arg(1'000)->Arg(10'000)->Unit(benchmark::kMillisecond);

// Baseline: the same network in the native ASCII format.
void BM_SwmmImportBaselineAscii(benchmark::State& state) {
  const std::string& text = texts_for(static_cast<std::size_t>(state.range(0))).ascii;
  SewerMap last;
  for (auto _ : state) {
    Diagnostics d;
    Result<SewerMap> map = read_map_ascii(text, "bench.sewer", d);
    if (!map.has_value()) return state.SkipWithError(map.error().message.c_str());
    last = std::move(*map);
  }
  report(state, last, text.size());
}
BENCHMARK(BM_SwmmImportBaselineAscii)->Arg(1'000)->Arg(10'000)->Unit(benchmark::kMillisecond);

const char* const kSharedFiles[] = {"swmm/epa-example1.inp", "swmm/swmmio-state-plane.inp",
                                    "swmm/bellinge-small.inp", "isybau/street-2006.xml",
                                    "isybau/street-2017.xml"};

// The datasets, by index into kSharedFiles.
void BM_SharedFileImport(benchmark::State& state) {
  const std::string file = kSharedFiles[state.range(0)];
  state.SetLabel(file);
  Result<std::string> text =
      read_text_file(std::string(SEWERPLAN_SOURCE_DIR) + "/datasets/" + file);
  if (!text.has_value()) return state.SkipWithError(text.error().message.c_str());
  const bool swmm = file.ends_with(".inp");
  for (auto _ : state) {
    Diagnostics d;
    Result<SewerMap> map = swmm ? read_map_swmm(*text, file, d) : read_map_isybau(*text, file, d);
    if (!map.has_value()) return state.SkipWithError(map.error().message.c_str());
    benchmark::DoNotOptimize(map);
  }
}
BENCHMARK(BM_SharedFileImport)->DenseRange(0, 4)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace sewerplan
