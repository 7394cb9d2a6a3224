// SPDX-License-Identifier: MIT
#include "can_link.h"

#include <chrono>

#include "sewerplan/hal/can/slcan.h"
#include "sewerplan/hal/can/socketcan.h"

namespace sewerplan::cli {
namespace {

Result<std::unique_ptr<hal::CanBus>> open_bus(const CanLinkOptions& o) {
  if (!o.replay.empty()) {
    Result<std::vector<hal::CandumpRecord>> records = hal::read_candump_file(o.replay);
    if (!records.has_value()) return records.error();
    return std::unique_ptr<hal::CanBus>(
        std::make_unique<hal::ReplayCanBus>(std::move(*records), o.replay));
  }
  const auto colon = o.bus.find(':');
  const std::string kind = o.bus.substr(0, colon);
  const std::string where = colon == std::string::npos ? std::string() : o.bus.substr(colon + 1);
  if (kind == "slcan" && !where.empty()) {
    Result<std::unique_ptr<hal::SlcanBus>> bus = hal::SlcanBus::open(where, {.bitrate = o.bitrate});
    if (!bus.has_value()) return bus.error();
    return std::unique_ptr<hal::CanBus>(std::move(*bus));
  }
  if (kind == "socketcan" && !where.empty()) {
    Result<std::unique_ptr<hal::SocketCanBus>> bus = hal::SocketCanBus::open(where);
    if (!bus.has_value()) return bus.error();
    return std::unique_ptr<hal::CanBus>(std::move(*bus));
  }
  return Error{ErrorCode::kInvalidArgument,
               "--can: expected slcan:TTY or socketcan:INTERFACE, got '" + o.bus + "'"};
}

}  // namespace

double WallClock::now_s() const {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

Result<std::unique_ptr<CanLink>> CanLink::open(const CanLinkOptions& options) {
  std::unique_ptr<CanLink> link(new CanLink());  // NOLINT: private constructor
  Result<std::unique_ptr<hal::CanBus>> bus = open_bus(options);
  if (!bus.has_value()) return bus.error();
  link->bus_ = std::move(*bus);
  hal::CanBus* robot_bus = link->bus_.get();
  if (!options.log.empty()) {
    Result<LogFile> log = LogFile::open(options.log);
    if (!log.has_value()) return log.error();
    link->log_.emplace(std::move(*log));
    link->recording_.emplace(*link->bus_, *link->log_, link->wall_);
    robot_bus = &*link->recording_;
  }
  link->robot_.emplace(*robot_bus);
  if (Result<void> up = link->robot_->connect(); !up.has_value()) return up.error();
  return link;
}

void CanLink::write_summary(std::ostream& out) const {
  const hal::CanLinkStats& s = robot_->stats();
  out << "CAN link " << bus_->name() << ": " << s.retries << " retries, " << s.timeouts
      << " timeouts, " << s.bad_input << " bad inputs, " << s.bus_errors << " bus errors, "
      << s.link_failures << " link failures\n";
}

Result<void> CanLink::close_log() {
  if (!log_) return {};
  return log_->close();
}

}  // namespace sewerplan::cli
