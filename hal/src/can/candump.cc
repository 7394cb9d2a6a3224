// SPDX-License-Identifier: MIT
#include "sewerplan/hal/can/candump.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "sewerplan/core/text_file.h"
#include "sewerplan/hal/can/job_protocol.h"

#include "can_text.h"

namespace sewerplan::hal {
namespace {

bool is_controller_heartbeat(const CanFrame& frame) {
  const std::optional<FrameId> id = frame_id(frame);
  return id && id->type == MessageType::kControllerHeartbeat;
}

bool from_node(const CanFrame& frame) {
  const std::optional<FrameId> id = frame_id(frame);
  // Frames of other protocols are played back too: the controller must ignore them.
  return !id || sent_by_node(id->type);
}

}  // namespace

std::string candump_line(const CandumpRecord& record) {
  const double t = std::max(0.0, record.time_s);
  auto seconds = static_cast<unsigned long long>(t);  // NOLINT
  auto micros = static_cast<unsigned long long>(
      std::llround((t - static_cast<double>(seconds)) * 1e6));  // NOLINT
  if (micros >= 1000000) {
    ++seconds;
    micros -= 1000000;
  }
  std::array<char, 48> stamp{};
  std::snprintf(stamp.data(), stamp.size(), "(%010llu.%06llu)", seconds, micros);
  return std::string(stamp.data()) + ' ' + record.interface + ' ' + to_candump_text(record.frame);
}

Result<CandumpRecord> parse_candump_line(std::string_view line) {
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.remove_suffix(1);
  if (line.size() < 3 || line[0] != '(') {
    return Error{ErrorCode::kParse,
                 "expected '(SECONDS.MICROS) INTERFACE ID#DATA', found '" + printable(line) + "'"};
  }
  const auto close = line.find(')');
  if (close == std::string_view::npos) return Error{ErrorCode::kParse, "no ')' after the time"};
  const std::string_view stamp = line.substr(1, close - 1);
  const auto dot = stamp.find('.');
  std::uint64_t seconds = 0;
  std::uint64_t micros = 0;
  const auto digits = [](std::string_view text, std::uint64_t& value) {
    if (text.empty() || text.size() > 19) return false;
    value = 0;
    for (char c : text) {
      if (c < '0' || c > '9') return false;
      value = value * 10 + static_cast<std::uint64_t>(c - '0');
    }
    return true;
  };
  if (dot == std::string_view::npos || !digits(stamp.substr(0, dot), seconds) ||
      stamp.size() - dot - 1 != 6 || !digits(stamp.substr(dot + 1), micros)) {
    return Error{ErrorCode::kParse, "bad time '" + printable(stamp) + "' (SECONDS.MICROS)"};
  }
  std::string_view rest = line.substr(close + 1);
  if (rest.empty() || rest[0] != ' ')
    return Error{ErrorCode::kParse, "expected ' ' after the time"};
  rest.remove_prefix(1);
  const auto space = rest.find(' ');
  if (space == std::string_view::npos || space == 0) {
    return Error{ErrorCode::kParse, "expected 'INTERFACE ID#DATA' after the time"};
  }
  CandumpRecord record;
  record.time_s = static_cast<double>(seconds) + static_cast<double>(micros) * 1e-6;
  record.interface = std::string(rest.substr(0, space));
  std::string_view frame_text = rest.substr(space + 1);
  // candump -l may add a direction or flags after the frame ("T", "R"): dropped.
  if (const auto more = frame_text.find(' '); more != std::string_view::npos) {
    frame_text = frame_text.substr(0, more);
  }
  Result<CanFrame> frame = parse_candump_frame(frame_text);
  if (!frame.has_value()) return frame.error();
  record.frame = *frame;
  return record;
}

Result<std::vector<CandumpRecord>> read_candump(std::istream& in, const std::string& file_name) {
  std::vector<CandumpRecord> records;
  std::string line;
  std::size_t number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    Result<CandumpRecord> record = parse_candump_line(line);
    if (!record.has_value()) {
      return Error{ErrorCode::kParse,
                   file_name + ":" + std::to_string(number) + ": " + record.error().message};
    }
    record->line = number;
    records.push_back(std::move(*record));
  }
  return records;
}

Result<std::vector<CandumpRecord>> read_candump_file(const std::filesystem::path& path) {
  // The one reader of input files (core/text_file.h): a FIFO or a device is refused, not waited on.
  Result<std::string> text = read_text_file(path);
  if (!text.has_value()) return text.error();
  std::istringstream in(std::move(*text));
  return read_candump(in, path.string());
}

RecordingCanBus::RecordingCanBus(CanBus& inner, std::ostream& out, const Clock& clock,
                                 std::string interface)
    : inner_(inner), out_(&out), clock_(clock), interface_(std::move(interface)) {}

RecordingCanBus::RecordingCanBus(CanBus& inner, LogFile& log, const Clock& clock,
                                 std::string interface)
    : inner_(inner), log_(&log), clock_(clock), interface_(std::move(interface)) {}

void RecordingCanBus::write(const CanFrame& frame) {
  const std::string line = candump_line(CandumpRecord{clock_.now_s(), interface_, frame, 0});
  if (log_ != nullptr) {
    log_->append(line + '\n');
  } else {
    *out_ << line << '\n';
  }
}

Result<void> RecordingCanBus::send(const CanFrame& frame) {
  Result<void> sent = inner_.send(frame);
  if (sent.has_value()) write(frame);
  return sent;
}

Result<std::optional<CanFrame>> RecordingCanBus::receive(double timeout_s) {
  Result<std::optional<CanFrame>> in = inner_.receive(timeout_s);
  if (in.has_value() && in->has_value()) write(**in);
  return in;
}

ReplayCanBus::ReplayCanBus(std::vector<CandumpRecord> records, std::string file_name)
    : file_name_(std::move(file_name)) {
  for (CandumpRecord& r : records) {
    if (from_node(r.frame)) {
      from_node_.push_back(std::move(r));
    } else if (!is_controller_heartbeat(r.frame)) {
      from_controller_.push_back(std::move(r));
    }
  }
}

Result<void> ReplayCanBus::send(const CanFrame& frame) {
  if (is_controller_heartbeat(frame)) return {};
  if (next_out_ >= from_controller_.size()) {
    return Error{ErrorCode::kBusError, name() + ": the controller sent " + to_candump_text(frame) +
                                           " after the end of the log"};
  }
  const CandumpRecord& expected = from_controller_[next_out_];
  if (!(expected.frame == frame)) {
    return Error{ErrorCode::kBusError, name() + ":" + std::to_string(expected.line) +
                                           ": the controller sent " + to_candump_text(frame) +
                                           " where the log has " + to_candump_text(expected.frame)};
  }
  ++next_out_;
  return {};
}

Result<std::optional<CanFrame>> ReplayCanBus::receive(double /*timeout_s*/) {
  if (next_in_ >= from_node_.size()) return std::optional<CanFrame>();
  return std::optional<CanFrame>(from_node_[next_in_++].frame);
}

std::size_t ReplayCanBus::unsent() const { return from_controller_.size() - next_out_; }

}  // namespace sewerplan::hal
