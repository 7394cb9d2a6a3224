// SPDX-License-Identifier: MIT
// The objects of an ISYBAU document and the elements that hold their measured values, shared by
// the importer (map_isybau.cc) and the writer of a corrected copy (isybau_correction.cc), so that
// both look at the same elements. Private to core/src (pugixml is a private dependency of core).
//
//   for (pugi::xml_node object : detail::isybau_objects(doc.document_element())) { ... }
//
// Thread safety: Free functions that share nothing.
#pragma once

#include <string_view>
#include <vector>

#include <pugixml.hpp>

namespace sewerplan::detail {

// Every AbwassertechnischeAnlage of the document, in document order, and every
// InspizierteAbwassertechnischeAnlage (Zustandsdaten) into `inspected`. Runtime: O(elements).
std::vector<pugi::xml_node> isybau_objects(pugi::xml_node root,
                                           std::vector<pugi::xml_node>* inspected = nullptr);

// The first element named `name` below `node`, at any depth, in document order (ISYBAU versions
// nest the length elements differently). Runtime: O(size of the subtree).
pugi::xml_node find_below(pugi::xml_node node, std::string_view name);

// The Punkt that gives a node's position (Rechtswert, Hochwert): the first Punkt of the object's
// Geometrie/Geometriedaten/Knoten; empty if it has none.
pugi::xml_node isybau_position_point(pugi::xml_node object);

}  // namespace sewerplan::detail
