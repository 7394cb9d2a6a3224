// SPDX-License-Identifier: MIT
#include "sewerplan/executor/recovery.h"

#include <cstdint>
#include <set>

#include "sewerplan/core/json_fields.h"
#include "sewerplan/executor/recovery_clears.h"

namespace sewerplan::executor {
namespace {

constexpr auto kOptional = JsonFields::Need::kOptional;
constexpr std::string_view kRecoveryJsonFormat = "sewerplan-recovery";

// Backing off or backing up farther than this is no recovery move.
constexpr double kMaxDistance_m = 10;

// The lists of a profile file, one per error, and the error each answers.
struct ErrorList {
  std::string_view key;
  hal::RobotErrorKind error;
};
constexpr std::array<ErrorList, 3> kErrorLists{{
    {"malfunction", hal::RobotErrorKind::kMalfunction},
    {"blockage", hal::RobotErrorKind::kBlockage},
    {"danger", hal::RobotErrorKind::kDanger},
}};

const RecoveryManoeuvre* manoeuvre_named(std::string_view name) {
  for (const RecoveryManoeuvre& m : kRecoveryManoeuvres) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

std::string names_of(hal::RobotErrorKind error) {
  std::string names;
  for (const RecoveryManoeuvre& m : kRecoveryManoeuvres) {
    if (m.error != error) continue;
    names += (names.empty() ? "\"" : ", \"") + std::string(m.name) + "\"";
  }
  return names;
}

// One row of an error's list; nullopt (with the error reported) when it is not one.
std::optional<RecoveryStage> read_stage(JsonElement element, const std::string& path,
                                        const ErrorList& list, std::string_view file,
                                        Diagnostics& diagnostics) {
  JsonFields f(element, path, file, diagnostics);
  if (!f.is_object()) return std::nullopt;
  f.reject_unknown({"manoeuvre", "tries", "distance_m"});
  const std::optional<std::string> name = f.string("manoeuvre");
  if (!name) return std::nullopt;
  const RecoveryManoeuvre* m = manoeuvre_named(*name);
  if (m == nullptr || m->error != list.error) {
    f.error("manoeuvre", "expected a manoeuvre for a " + std::string(list.key) + " (" +
                             names_of(list.error) + "), got \"" + *name + "\"");
    return std::nullopt;
  }
  RecoveryStage stage{.phase = m->phase, .tries = 1};
  const auto max = static_cast<std::uint64_t>(m->max_tries);
  if (const std::optional<std::uint64_t> tries = f.count("tries", max, kOptional)) {
    stage.tries = static_cast<int>(*tries);
  }
  if (!m->drives) {
    if (f.has("distance_m")) f.error("distance_m", "\"" + *name + "\" drives no distance");
    return stage;
  }
  const std::optional<double> distance = f.number("distance_m");
  if (!distance) return std::nullopt;
  if (*distance < 0 || *distance > kMaxDistance_m) {
    f.error("distance_m", "expected metres from 0 to 10, got " + format_double(*distance));
    return std::nullopt;
  }
  stage.distance_m = *distance;
  return stage;
}

}  // namespace

const RecoveryStage* RecoveryProfile::stage(RecoveryPhase phase) const {
  for (const RecoveryStage& s : stages) {
    if (s.phase == phase) return &s;
  }
  return nullptr;
}

int RecoveryProfile::tries(const RecoveryStage& s) const {
  return s.phase == RecoveryPhase::kPush && !push_allowed ? 0 : s.tries;
}

int RecoveryProfile::tries(RecoveryPhase phase) const {
  const RecoveryStage* s = stage(phase);
  return s == nullptr ? 0 : tries(*s);
}

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

bool recovery_clears(const RecoveryProfile& config, hal::ObstacleKind kind,
                     hal::Approach approach) {
  if (!hal::clears_from(kind, approach)) return false;
  for (const RecoveryStage& stage : config.stages) {
    if (manoeuvre(stage.phase).error == hal::RobotErrorKind::kBlockage &&
        manoeuvre_of(stage.phase) == hal::cleared_by(kind) && config.tries(stage) > 0) {
      return true;
    }
  }
  return false;
}

Result<RecoveryProfile> read_recovery_json(std::string_view text, const std::string& file_name) {
  Diagnostics diagnostics;
  std::optional<JsonDocument> doc = JsonDocument::parse(text, file_name, diagnostics);
  if (!doc) return Error{ErrorCode::kParse, diagnostics.error_summary()};
  JsonFields f(doc->root(), "$", file_name, diagnostics);
  f.reject_unknown({"format", "version", "malfunction", "blockage", "danger", "push_allowed"});
  if (const auto format = f.string("format"); format && *format != kRecoveryJsonFormat) {
    f.error("format",
            "expected \"" + std::string(kRecoveryJsonFormat) + "\", got \"" + *format + "\"");
  }
  if (const auto version = f.count("version", 1000); version && *version != 1) {
    f.error("version", "expected 1, got " + std::to_string(*version));
  }
  RecoveryProfile profile;
  if (std::optional<bool> push = f.boolean("push_allowed", kOptional)) profile.push_allowed = *push;
  // Each error's rows: the file's list, else the default table's.
  std::vector<RecoveryStage> stages;
  for (const ErrorList& list : kErrorLists) {
    const std::optional<JsonArray> rows = f.array(list.key, kOptional);
    if (!rows) {
      if (f.has(list.key)) continue;  // not an array: reported
      for (const RecoveryStage& s : kRecoveryTable) {
        if (manoeuvre(s.phase).error == list.error) stages.push_back(s);
      }
      continue;
    }
    const std::string path = "$." + std::string(list.key);
    std::set<RecoveryPhase> seen;
    std::size_t i = 0;
    for (JsonElement row : *rows) {
      const std::string where = indexed(path, i++);
      std::optional<RecoveryStage> stage = read_stage(row, where, list, file_name, diagnostics);
      if (!stage) continue;
      if (!seen.insert(stage->phase).second) {
        diagnostics.error(file_name + ":" + where + ".manoeuvre",
                          "\"" + std::string(manoeuvre(stage->phase).name) +
                              "\" given twice: one row per manoeuvre, its tries say how often");
        continue;
      }
      stages.push_back(*stage);
    }
  }
  if (diagnostics.has_errors()) return Error{ErrorCode::kParse, diagnostics.error_summary()};
  profile.stages = std::move(stages);
  return profile;
}

}  // namespace sewerplan::executor
