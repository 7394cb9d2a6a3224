// SPDX-License-Identifier: MIT
#include "sewerplan/core/text_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <system_error>

namespace sewerplan {

Result<std::string> read_text_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    return Error{ErrorCode::kIo, "cannot read " + path.string() + ": it is a directory"};
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    return Error{ErrorCode::kIo, "cannot read " + path.string() + ": " + std::strerror(errno)};
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) {
    return Error{ErrorCode::kIo, "cannot read " + path.string() + ": read error"};
  }
  return std::move(text).str();
}

Result<void> write_text_file(const std::filesystem::path& path, std::string_view text) {
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) {
      return Error{ErrorCode::kIo, "cannot write " + path.string() + ": " + std::strerror(errno)};
    }
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.flush();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(tmp, ignored);
      return Error{ErrorCode::kIo, "cannot write " + path.string() + ": write error"};
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    return Error{ErrorCode::kIo, "cannot write " + path.string() + ": " + ec.message()};
  }
  return {};
}

}  // namespace sewerplan
