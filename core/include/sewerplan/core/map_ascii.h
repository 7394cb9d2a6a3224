// SPDX-License-Identifier: MIT
// The ASCII sewer database: MAKRO's own plain-text map format, read and written.
//
// Adria, Streich and Hertzberg 2004 (section 4.2): "The current internal database used in MAKRO's
// Planning System is an ASCII text. We set the format ourselves; it includes the manhole's
// diameter, connections and the gross connection angles between the different pipes. The pipe
// info stored is the length and the diameter." The paper gives no syntax; sewerplan's is a
// line-oriented text, one object per line, specified in docs/formats/ascii-database.md:
//
//   sewerdb 1
//   map ais-testbed
//   manhole M2 x=0 y=0 z=0 diameter=1 exit variant=B
//     slot P12 azimuth=180 invert=0
//   pipe P12 from=M1 to=M2 length=8.5 diameter=0.6
//   point W1 pipe=P12 offset=2.5
//
// The reader turns lines into MapBuilder records (map_builder.h), so the map is validated like a
// map in any other format; every diagnostic, of syntax or of the network, names "file:line". The
// writer's output is canonical (one text per map) and loses nothing: reading it gives back a map
// equal to the one written.
//
//   Diagnostics diagnostics;
//   Result<SewerMap> map = read_map_ascii(text, "maps/ais.sewer", diagnostics);
//   if (!map.has_value()) return map.error();  // kParse or kInvalidMap, listing every problem
//   std::ostringstream out;
//   Result<void> written = write_map_ascii(*map, out);
//
// Thread safety: The readers and writers share nothing: call them from any number of threads, each
// with its own Diagnostics.
#pragma once

#include <ostream>
#include <string>
#include <string_view>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan {

// Reads a map from `text`, the content of the file `file_name` (used in diagnostics, and its stem,
// "ais" for "maps/ais.sewer", names the map when the text has no `map` line).
//
// Syntax errors are each added to `diagnostics` as "file:line" and reading goes on with the next
// line, so that all of them are reported at once; if there were any, the result is a kParse Error
// listing them and no map is built. A file of another format version, or one not starting like a
// sewerdb file, is not read past its first line. Otherwise the records go to MapBuilder, whose
// errors (kInvalidMap) and warnings also name the line. Never throws, whatever the input.
// Runtime: O(n log n) in the size of the text.
Result<SewerMap> read_map_ascii(std::string_view text, const std::string& file_name,
                                Diagnostics& diagnostics);

// Writes `map` to `out` in the canonical form: a comment, the header, the map name, every manhole
// in map order with its slots indented below it, then the pipes, then the inspection points;
// numbers in their shortest exact form, optional keys only where they differ from their default.
//
// Fails with kInvalidArgument, writing nothing, if a name cannot be written as one token (empty,
// starting with '#', containing '=' or white space, or a manhole called "-"); the message names
// every such object. Fails with kIo if the stream fails. Runtime: O(size of the map).
Result<void> write_map_ascii(const SewerMap& map, std::ostream& out);

}  // namespace sewerplan
