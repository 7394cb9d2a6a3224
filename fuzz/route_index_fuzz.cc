// SPDX-License-Identifier: MIT
// libFuzzer target: the routing index reader (domain/route_index.h, docs/formats/route-index.md).
// The checksum over the body is written into the input first, so that the fuzzer reaches the
// structural checks behind it rather than stopping at the checksum. An index the reader accepts
// must answer queries and unpack its ways without a fault, and write back the same bytes.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "sewerplan/domain/route_index.h"

#include "fuzz_support.h"
#include "route_index_internal.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(sewerplan::fuzz::as_text(data, size));
  if (bytes.size() >= 64) {
    const std::uint64_t hash =
        sewerplan::domain::detail::file_checksum(std::string_view(bytes).substr(64));
    for (std::size_t i = 0; i < 8; ++i)
      bytes[56 + i] = static_cast<char>((hash >> (8 * i)) & 0xffU);
  }
  const auto index = sewerplan::domain::RouteIndex::read(bytes, "fuzz.bin");
  if (!index.has_value()) return 0;
  if (index->bytes() != bytes) std::abort();  // what was read is what is written
  const auto& ch = *index->impl().hierarchy;
  sewerplan::domain::detail::ChQuery query(ch);
  const auto n = static_cast<sewerplan::domain::detail::Node>(ch.size());
  std::vector<sewerplan::domain::detail::Node> way;
  std::vector<sewerplan::domain::detail::Node> ends;
  for (sewerplan::domain::detail::Node s = 0; s < std::min<std::size_t>(n, 6); ++s) {
    ends.push_back(n - 1 - s);
    for (sewerplan::domain::detail::Node t = 0; t < std::min<std::size_t>(n, 6); ++t) {
      bool unique = false;
      (void)query.path(s, n - 1 - t, way, &unique);
    }
  }
  sewerplan::domain::detail::ChTable table;
  query.table_with_ways(ends, ends, table);
  for (std::size_t i = 0; i < ends.size(); ++i) {
    for (std::size_t j = 0; j < ends.size(); ++j) table.way(i, j, way);
  }
  return 0;
}
