// SPDX-License-Identifier: MIT
// The bus-fault specification of the simulated node: "drop=3,7;garbage=2;silence=10+3;...".
#include <charconv>
#include <cmath>
#include <string>

#include "sewerplan/hal/can/sim_node.h"

namespace sewerplan::hal {
namespace {

Error bad(std::string_view item, const std::string& what) {
  return Error{ErrorCode::kInvalidArgument, "--bus-faults: '" + std::string(item) + "': " + what};
}

std::optional<std::uint64_t> count_of(std::string_view text) {
  std::uint64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty()) return std::nullopt;
  return value;
}

std::optional<double> number_of(std::string_view text) {
  // std::from_chars for double is missing from libstdc++ before 11 and from libc++ 14.
  if (text.empty() || text.size() > 32) return std::nullopt;
  const std::string s(text);
  std::size_t used = 0;
  try {
    const double value = std::stod(s, &used);
    if (used != s.size() || !std::isfinite(value)) return std::nullopt;
    return value;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

Result<std::vector<std::uint64_t>> counts_of(std::string_view item, std::string_view list) {
  std::vector<std::uint64_t> values;
  while (!list.empty()) {
    const auto comma = list.find(',');
    const std::optional<std::uint64_t> v = count_of(list.substr(0, comma));
    if (!v) return bad(item, "expected a list of frame numbers (0, 1, ...)");
    values.push_back(*v);
    list = comma == std::string_view::npos ? std::string_view() : list.substr(comma + 1);
  }
  if (values.empty()) return bad(item, "expected a list of frame numbers (0, 1, ...)");
  return values;
}

}  // namespace

Result<BusFaults> parse_bus_faults(std::string_view spec) {
  BusFaults faults;
  while (!spec.empty()) {
    const auto semicolon = spec.find(';');
    const std::string_view item = spec.substr(0, semicolon);
    spec = semicolon == std::string_view::npos ? std::string_view() : spec.substr(semicolon + 1);
    if (item.empty()) continue;
    const auto eq = item.find('=');
    if (eq == std::string_view::npos) return bad(item, "expected NAME=VALUE");
    const std::string_view name = item.substr(0, eq);
    const std::string_view value = item.substr(eq + 1);
    if (name == "drop" || name == "garbage" || name == "lose-result") {
      Result<std::vector<std::uint64_t>> list = counts_of(item, value);
      if (!list.has_value()) return list.error();
      (name == "drop"      ? faults.drop_frames
       : name == "garbage" ? faults.garbage_before
                           : faults.lose_results) = *list;
    } else if (name == "drop-rate") {
      const std::optional<double> rate = number_of(value);
      if (!rate || *rate < 0 || *rate > 1) return bad(item, "expected a probability in [0, 1]");
      faults.drop_rate = *rate;
    } else if (name == "seed") {
      const std::optional<std::uint64_t> seed = count_of(value);
      if (!seed) return bad(item, "expected a number");
      faults.seed = *seed;
    } else if (name == "silence") {
      const auto plus = value.find('+');
      const std::optional<std::uint64_t> from = count_of(value.substr(0, plus));
      const std::optional<std::uint64_t> n = plus == std::string_view::npos
                                                 ? std::optional<std::uint64_t>(1)
                                                 : count_of(value.substr(plus + 1));
      if (!from || !n || *n == 0) return bad(item, "expected REQUEST[+COUNT]");
      faults.silence = Silence{*from, *n};
    } else if (name == "bus-off") {
      const std::optional<std::uint64_t> at = count_of(value);
      if (!at) return bad(item, "expected a request number");
      faults.bus_off_at = *at;
    } else if (name == "late-ack") {
      const auto at = value.find('@');
      const std::optional<std::uint64_t> job = count_of(value.substr(0, at));
      const std::optional<double> delay = at == std::string_view::npos
                                              ? std::optional<double>(1.0)
                                              : number_of(value.substr(at + 1));
      if (!job || !delay || *delay < 0 || *delay > 60) {
        return bad(item, "expected JOB[@SECONDS], 0 to 60 s");
      }
      faults.late_ack = LateAck{*job, *delay};
    } else {
      return bad(item,
                 "unknown fault (drop, drop-rate, seed, garbage, silence, bus-off, late-ack, "
                 "lose-result)");
    }
  }
  return faults;
}

std::ostream& operator<<(std::ostream& os, const BusFaults& faults) {
  const char* sep = "";
  const auto list = [&](const char* name, const std::vector<std::uint64_t>& values) {
    if (values.empty()) return;
    os << sep << name << '=';
    for (std::size_t i = 0; i < values.size(); ++i) os << (i > 0 ? "," : "") << values[i];
    sep = ";";
  };
  list("drop", faults.drop_frames);
  list("garbage", faults.garbage_before);
  list("lose-result", faults.lose_results);
  if (faults.drop_rate > 0) {
    os << sep << "drop-rate=" << faults.drop_rate << ";seed=" << faults.seed;
    sep = ";";
  }
  if (faults.silence) {
    os << sep << "silence=" << faults.silence->from_request << '+' << faults.silence->requests;
    sep = ";";
  }
  if (faults.bus_off_at) {
    os << sep << "bus-off=" << *faults.bus_off_at;
    sep = ";";
  }
  if (faults.late_ack)
    os << sep << "late-ack=" << faults.late_ack->job << '@' << faults.late_ack->delay_s;
  return os;
}

}  // namespace sewerplan::hal
