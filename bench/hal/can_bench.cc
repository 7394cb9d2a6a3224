// SPDX-License-Identifier: MIT
// The CAN code's speed: the job protocol's codec, the SLCAN line codec against a naive sscanf
// parser, and a whole job's round trip through a pseudo-terminal to the simulated node against the
// simulated robot in process.
#include <atomic>
#include <cstdio>
#include <thread>

#include <benchmark/benchmark.h>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/hal/can/can_robot.h"
#include "sewerplan/hal/can/job_protocol.h"
#include "sewerplan/hal/can/sim_node.h"
#include "sewerplan/hal/can/slcan.h"
#include "sewerplan/hal/sim_robot.h"

namespace sewerplan::hal {
namespace {

// A job and its result, encoded and decoded: the protocol work of one exchange.
void BM_JobProtocolRoundTrip(benchmark::State& state) {
  const JobCommand job{7, DriveForward{0.3, 12.5}};
  JobReport report;
  report.progress_m = 12.5;
  report.duration_s = 41.6;
  const JobResult result{7, report, RobotStatus{200, 100, 1000, false, false}};
  std::size_t frames = 0;
  for (auto _ : state) {
    MessageDecoder decoder;
    for (const Message& m : {Message(job), Message(result)}) {
      for (const CanFrame& f : encode(m)) {
        benchmark::DoNotOptimize(decoder.push(f));
        ++frames;
      }
    }
  }
  state.counters["frames/s"] =
      benchmark::Counter(static_cast<double>(frames), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_JobProtocolRoundTrip);

const char* const kLine = "T0220700087B14AE147AE2940";

void BM_SlcanParseFrame(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(parse_slcan_frame(kLine));
  state.counters["frames/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SlcanParseFrame);

// The naive baseline: sscanf for the identifier, the length and each byte.
void BM_SscanfParseFrame(benchmark::State& state) {
  for (auto _ : state) {
    unsigned id = 0;
    unsigned dlc = 0;
    std::array<unsigned, 8> data{};
    benchmark::DoNotOptimize(std::sscanf(kLine + 1, "%8x%1u", &id, &dlc));  // NOLINT
    for (unsigned i = 0; i < dlc && i < 8; ++i) {
      benchmark::DoNotOptimize(std::sscanf(kLine + 10 + 2 * i, "%2x", &data[i]));  // NOLINT
    }
    benchmark::DoNotOptimize(data);
  }
  state.counters["frames/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SscanfParseFrame);

// Frames to lines and back through the splitter, as a line carries them.
void BM_SlcanEncodeSplitParse(benchmark::State& state) {
  const std::vector<CanFrame> frames = encode(JobResult{3, {}, {}});
  SlcanSplitter splitter;
  std::size_t n = 0;
  for (auto _ : state) {
    for (const CanFrame& f : frames) splitter.feed(encode_slcan_frame(f));
    while (std::optional<SlcanSplitter::Token> t = splitter.next()) {
      benchmark::DoNotOptimize(parse_slcan_frame(t->text));
      ++n;
    }
  }
  state.counters["frames/s"] =
      benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SlcanEncodeSplitParse);

SewerMap ais_map() {
  Diagnostics d;
  Result<SewerMap> map =
      read_map(std::string(SEWERPLAN_SOURCE_DIR) + "/datasets/ais-testbed/map.json", d);
  return std::move(*map);
}

SimPose start(const SewerMap& map) {
  return InPipe{*map.find_pipe("P12"), 0, Heading::kTowardsEnd1};
}

// The baseline: the same job on the simulated robot in process.
void BM_SimRobotJobInProcess(benchmark::State& state) {
  const SewerMap map = ais_map();
  SimRobot robot(map, *builtin_profile("makro-1.1"), start(map));
  for (auto _ : state) benchmark::DoNotOptimize(robot.execute(TakeSample{0}));
}
BENCHMARK(BM_SimRobotJobInProcess);

// One job over SLCAN through a pty to the simulated node on its own thread, and its report back.
void BM_CanJobRoundTripPty(benchmark::State& state) {
  const SewerMap map = ais_map();
  SimRobot robot(map, *builtin_profile("makro-1.1"), start(map));
  Result<Pty> pty = open_pty();
  if (!pty.has_value()) {
    state.SkipWithError(pty.error().message.c_str());
    return;
  }
  SlcanDeviceBus line(std::move(pty->master), pty->slave_path);
  SimNode node(line, robot, {.heartbeat_s = 0}, &line);
  Result<std::unique_ptr<SlcanBus>> bus = SlcanBus::open(pty->slave_path, {});
  std::atomic<bool> stop{false};
  std::thread server([&] { static_cast<void>(node.serve(stop)); });
  CanRobot can(**bus, {});
  if (!can.connect().has_value()) state.SkipWithError("no node");
  for (auto _ : state) benchmark::DoNotOptimize(can.execute(TakeSample{0}));
  stop = true;
  server.join();
  state.counters["jobs/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_CanJobRoundTripPty)->UseRealTime();

}  // namespace
}  // namespace sewerplan::hal
