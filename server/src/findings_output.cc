// SPDX-License-Identifier: MIT
#include "sewerplan/server/findings_output.h"

#include <string>

#include "sewerplan/core/condition.h"
#include "sewerplan/core/map_discrepancy.h"

namespace sewerplan::server {

using Json = nlohmann::ordered_json;

Json findings_json(const SewerMap& map, const RobotProfile& profile, RiskMode mode,
                   std::string_view mode_name, const RiskTable& table) {
  Json list = Json::array();
  std::size_t closed = 0, weighed = 0, ignored = 0;
  for (const FindingRisk& r : assess_findings(map, profile, table)) {
    const Finding& f = map.findings()[r.finding];
    const FindingUse use = finding_use(r, mode);
    (use == FindingUse::kClosed ? closed : use == FindingUse::kWeighed ? weighed : ignored) += 1;
    Json j = {{"pipe", map.pipe(f.pipe).name},
              {"offset_m", f.offset_m},
              {"code", f.code},
              {"name", std::string(finding_code_name(f.code))},
              {"characterisation", f.characterisation}};
    if (f.quantity1) j["quantity1"] = *f.quantity1;
    if (f.quantity2) j["quantity2"] = *f.quantity2;
    j["class"] = std::string(to_string(r.effect));
    j["probability"] = r.blockage_probability;
    j["reason"] = r.reason;
    j["planner"] = std::string(to_string(use));
    list.push_back(std::move(j));
  }
  return {{"profile", profile.name},
          {"risk", std::string(mode_name)},
          {"findings", std::move(list)},
          {"counts", {{"closed", closed}, {"weighed", weighed}, {"ignored", ignored}}}};
}

Json learnt_json_document(const executor::Learnt& learnt, const MapMeasurements& measurements,
                          const SewerMap& map) {
  Json found = Json::array();
  for (const FoundDiscrepancy& d : discrepancies(measurements, map)) {
    const Discrepancy& x = d.discrepancy;
    Json j = {{"kind", std::string(to_string(x.kind))}};
    if (x.pipe) j["pipe"] = map.pipe(*x.pipe).name;
    if (x.manhole) j["manhole"] = map.manhole(*x.manhole).name;
    if (x.slot) j["slot"] = to_paper_number(*x.slot);  // from 1, as in missions and plans
    if (x.or_slot) j["or_slot"] = to_paper_number(*x.or_slot);
    j["offset_m"] = x.offset_m;
    j["map_value"] = x.map_value;
    j["value"] = x.value;
    j["sigma"] = x.sigma;
    j["text"] = describe(x, map);
    found.push_back(std::move(j));
  }
  return {{"learnt", Json::parse(executor::learnt_json(learnt, map))},
          {"measurements",
           {{"pipes_measured", measurements.pipes.size()},
            {"manholes_observed", measurements.manholes.size()},
            {"junctions", measurements.junctions.size()},
            {"discrepancies", std::move(found)}}}};
}

}  // namespace sewerplan::server
