// SPDX-License-Identifier: MIT
// The names of the risk effects (condition_risk.h), as risk tables and findings outputs write them:
// one table, read by to_string (condition_risk.cc) and by the risk table's reader
// (risk_table_json.cc).
//
// Private to core.
#pragma once

#include "sewerplan/core/condition_risk.h"
#include "sewerplan/core/enum_names.h"

namespace sewerplan::detail {

inline constexpr EnumNames<RiskEffect, 4> kRiskEffectNames{{
    {RiskEffect::kNone, "none"},
    {RiskEffect::kDanger, "danger"},
    {RiskEffect::kBlockage, "blockage"},
    {RiskEffect::kImpassable, "impassable"},
}};
static_assert(distinct(kRiskEffectNames));

}  // namespace sewerplan::detail
