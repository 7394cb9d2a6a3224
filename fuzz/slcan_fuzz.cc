// SPDX-License-Identifier: MIT
// libFuzzer target: the SLCAN line splitter and frame parser (hal/can/slcan.h), on bytes as a tty
// delivers them, in chunks; every frame that parses must survive encode and parse unchanged.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "sewerplan/hal/can/slcan.h"

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using sewerplan::hal::SlcanSplitter;
  const std::string_view bytes = sewerplan::fuzz::as_text(data, size);
  SlcanSplitter splitter;
  // The first byte picks the chunk size, as reads split the stream anywhere.
  const std::size_t chunk = size > 0 ? 1U + data[0] % 16U : 1U;
  for (std::size_t at = 0; at < bytes.size(); at += chunk) {
    splitter.feed(bytes.substr(at, chunk));
    while (std::optional<SlcanSplitter::Token> token = splitter.next()) {
      if (token->text.size() > sewerplan::hal::kMaxSlcanLine) std::abort();
      sewerplan::Result<sewerplan::hal::CanFrame> frame =
          sewerplan::hal::parse_slcan_frame(token->text);
      if (!frame.has_value()) continue;
      std::string line = sewerplan::hal::encode_slcan_frame(*frame);
      line.pop_back();
      sewerplan::Result<sewerplan::hal::CanFrame> again = sewerplan::hal::parse_slcan_frame(line);
      if (!again.has_value() || !(*again == *frame)) std::abort();
    }
  }
  return 0;
}
