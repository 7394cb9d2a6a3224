// SPDX-License-Identifier: MIT
#include "isybau_objects.h"

#include "condition_isybau.h"
#include "xml_support.h"

namespace sewerplan::detail {

using XmlNode = pugi::xml_node;

std::vector<XmlNode> isybau_objects(XmlNode root, std::vector<XmlNode>* inspected) {
  std::vector<XmlNode> objects;
  std::vector<XmlNode> stack{root};
  while (!stack.empty()) {
    const XmlNode n = stack.back();
    stack.pop_back();
    if (xml::local_name(n) == "AbwassertechnischeAnlage") {
      objects.push_back(n);
      continue;
    }
    if (xml::local_name(n) == "InspizierteAbwassertechnischeAnlage") {
      if (inspected != nullptr) inspected->push_back(n);
      continue;
    }
    std::vector<XmlNode> children;
    for (XmlNode c = n.first_child(); c; c = c.next_sibling()) {
      if (c.type() == pugi::node_element) children.push_back(c);
    }
    stack.insert(stack.end(), children.rbegin(), children.rend());
  }
  return objects;
}

XmlNode find_below(XmlNode node, std::string_view name) {
  std::vector<XmlNode> found;
  collect(node, name, found);
  return found.empty() ? XmlNode() : found.front();
}

XmlNode isybau_position_point(XmlNode object) {
  const XmlNode points = xml::descend(object, {"Geometrie", "Geometriedaten", "Knoten"});
  for (XmlNode p = points.first_child(); p; p = p.next_sibling()) {
    if (xml::local_name(p) == "Punkt") return p;
  }
  return {};
}

}  // namespace sewerplan::detail
