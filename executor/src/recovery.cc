// SPDX-License-Identifier: MIT
#include "sewerplan/executor/recovery.h"

#include <cstdint>

#include "sewerplan/core/json_fields.h"
#include "sewerplan/executor/recovery_clears.h"

namespace sewerplan::executor {
namespace {

constexpr auto kOptional = JsonFields::Need::kOptional;

// Tries of a recovery phase; more than this is no robot's.
constexpr std::uint64_t kMaxCount = 1000;
// Backing off or backing up farther than this is no recovery move.
constexpr double kMaxDistance_m = 10;

void read_count(JsonFields& f, std::string_view key, int& field) {
  if (const std::optional<std::uint64_t> v = f.count(key, kMaxCount, kOptional)) {
    field = static_cast<int>(*v);
  }
}

void read_distance(JsonFields& f, std::string_view key, double& field) {
  const std::optional<double> v = f.number(key, kOptional);
  if (!v) return;
  if (*v < 0 || *v > kMaxDistance_m) {
    f.error(key, "expected metres from 0 to 10, got " + format_double(*v));
    return;
  }
  field = *v;
}

}  // namespace

hal::Clearing manoeuvre_of(RecoveryPhase phase) {
  switch (phase) {
    case RecoveryPhase::kLiftHeadAndRetry:
      return hal::Clearing::kLiftHead;
    case RecoveryPhase::kPush:
      return hal::Clearing::kPush;
    case RecoveryPhase::kReboot:
    case RecoveryPhase::kBackUpAndRetry:
    case RecoveryPhase::kBackOffToSafety:
    case RecoveryPhase::kBackOutOfManhole:
      return hal::Clearing::kNothing;
  }
  return hal::Clearing::kNothing;
}

int stage_tries(const RecoveryConfig& config, RecoveryPhase phase) {
  switch (phase) {
    case RecoveryPhase::kReboot:
      return config.max_reboots;
    case RecoveryPhase::kBackUpAndRetry:
      return config.backup_retries;
    case RecoveryPhase::kLiftHeadAndRetry:
      return config.lift_retries;
    case RecoveryPhase::kPush:
      return config.push_allowed ? config.push_retries : 0;
    case RecoveryPhase::kBackOffToSafety:
    case RecoveryPhase::kBackOutOfManhole:
      return 1;
  }
  return 0;
}

bool recovery_clears(const RecoveryConfig& config, hal::ObstacleKind kind, hal::Approach approach) {
  if (!hal::clears_from(kind, approach)) return false;
  for (const RecoveryStage& stage : kRecoveryTable) {
    if (stage.error == hal::RobotErrorKind::kBlockage &&
        manoeuvre_of(stage.phase) == hal::cleared_by(kind) &&
        stage_tries(config, stage.phase) > 0) {
      return true;
    }
  }
  return false;
}

Result<RecoveryConfig> read_recovery_json(std::string_view text, const std::string& file_name) {
  Diagnostics diagnostics;
  std::optional<JsonDocument> doc = JsonDocument::parse(text, file_name, diagnostics);
  if (!doc) return Error{ErrorCode::kParse, diagnostics.error_summary()};
  JsonFields f(doc->root(), "$", file_name, diagnostics);
  RecoveryConfig c;
  f.reject_unknown({"backup_retries", "backup_m", "lift_retries", "push_retries",
                    "danger_backoff_m", "max_reboots", "push_allowed"});
  read_count(f, "backup_retries", c.backup_retries);
  read_distance(f, "backup_m", c.backup_m);
  read_count(f, "lift_retries", c.lift_retries);
  read_count(f, "push_retries", c.push_retries);
  read_distance(f, "danger_backoff_m", c.danger_backoff_m);
  read_count(f, "max_reboots", c.max_reboots);
  if (std::optional<bool> push = f.boolean("push_allowed", kOptional)) c.push_allowed = *push;
  if (diagnostics.has_errors()) return Error{ErrorCode::kParse, diagnostics.error_summary()};
  return c;
}

}  // namespace sewerplan::executor
