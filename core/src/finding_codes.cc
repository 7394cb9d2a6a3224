// SPDX-License-Identifier: MIT
// The main codes of DIN EN 13508-2 for pipes (sewers and drains), with their English names: A..
// structural (BA.), operational (BB.) and inventory (BC.) codes, and the inspection's own remarks
// (BD.). The risk table (condition_risk.h) decides what they mean for a robot; this only names
// them.
#include <array>
#include <string_view>
#include <utility>

#include "sewerplan/core/condition.h"

namespace sewerplan {
namespace {

constexpr std::array<std::pair<std::string_view, std::string_view>, 36> kCodes{{
    {"BAA", "deformation"},
    {"BAB", "crack"},
    {"BAC", "break or collapse"},
    {"BAD", "defective brickwork or masonry"},
    {"BAE", "missing mortar"},
    {"BAF", "surface damage"},
    {"BAG", "intruding connection"},
    {"BAH", "defective connection"},
    {"BAI", "intruding sealing material"},
    {"BAJ", "displaced joint"},
    {"BAK", "lining feature"},
    {"BAL", "defective repair"},
    {"BAM", "weld failure"},
    {"BAN", "porous pipe"},
    {"BAO", "soil visible through defect"},
    {"BAP", "void visible through defect"},
    {"BBA", "roots"},
    {"BBB", "attached deposits"},
    {"BBC", "settled deposits"},
    {"BBD", "ingress of soil"},
    {"BBE", "other obstacles"},
    {"BBF", "infiltration"},
    {"BBG", "exfiltration"},
    {"BBH", "vermin"},
    {"BCA", "connection"},
    {"BCB", "point repair"},
    {"BCC", "curvature of the pipe"},
    {"BCD", "start node"},
    {"BCE", "finish node"},
    {"BDA", "general photograph"},
    {"BDB", "general remark"},
    {"BDC", "inspection abandoned"},
    {"BDD", "water level"},
    {"BDE", "flow from an incoming pipe"},
    {"BDF", "atmosphere in the pipe"},
    {"BDG", "loss of vision"},
}};

}  // namespace

std::string_view finding_code_name(std::string_view code) {
  for (const auto& [c, name] : kCodes) {
    if (c == code) return name;
  }
  return {};
}

}  // namespace sewerplan
