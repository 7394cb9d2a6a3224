// SPDX-License-Identifier: MIT
#include "sewerplan/core/text_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <system_error>

#include "sewerplan/core/ascii_case.h"

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
  // A regular file is read at once into a string of its size (a stream would grow and copy a
  // 430 MB map several times); anything else (a pipe) through the stream.
  const std::uintmax_t size = std::filesystem::is_regular_file(path, ec)
                                  ? std::filesystem::file_size(path, ec)
                                  : static_cast<std::uintmax_t>(-1);
  if (!ec && size != static_cast<std::uintmax_t>(-1)) {
    std::string text(static_cast<std::size_t>(size), '\0');
    in.read(text.data(), static_cast<std::streamsize>(size));
    const auto got = static_cast<std::size_t>(in.gcount());
    if (in.bad()) {
      return Error{ErrorCode::kIo, "cannot read " + path.string() + ": read error"};
    }
    text.resize(got);
    if (got == size) {
      // The file may have grown since: take the rest too.
      std::ostringstream rest;
      rest << in.rdbuf();
      text += std::move(rest).str();
    }
    return text;
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

bool is_valid_utf8(std::string_view text) {
  std::size_t i = 0;
  const std::size_t n = text.size();
  auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  auto continuation = [&](std::size_t k) { return k < n && (byte(k) & 0xC0) == 0x80; };
  while (i < n) {
    const unsigned char c = byte(i);
    if (c < 0x80) {
      ++i;
    } else if (c >= 0xC2 && c <= 0xDF) {
      if (!continuation(i + 1)) return false;
      i += 2;
    } else if (c >= 0xE0 && c <= 0xEF) {
      if (!continuation(i + 1) || !continuation(i + 2)) return false;
      const unsigned char c1 = byte(i + 1);
      if ((c == 0xE0 && c1 < 0xA0) || (c == 0xED && c1 >= 0xA0))
        return false;  // overlong, surrogate
      i += 3;
    } else if (c >= 0xF0 && c <= 0xF4) {
      if (!continuation(i + 1) || !continuation(i + 2) || !continuation(i + 3)) return false;
      const unsigned char c1 = byte(i + 1);
      if ((c == 0xF0 && c1 < 0x90) || (c == 0xF4 && c1 >= 0x90))
        return false;  // overlong, > U+10FFFF
      i += 4;
    } else {
      return false;
    }
  }
  return true;
}

std::string windows1252_to_utf8(std::string_view text) {
  // 0x80..0x9F in Windows-1252; 0xFFFD where it assigns nothing.
  static constexpr char32_t kC1[32] = {
      0x20AC, 0xFFFD, 0x201A, 0x0192, 0x201E, 0x2026, 0x2020, 0x2021, 0x02C6, 0x2030, 0x0160,
      0x2039, 0x0152, 0xFFFD, 0x017D, 0xFFFD, 0xFFFD, 0x2018, 0x2019, 0x201C, 0x201D, 0x2022,
      0x2013, 0x2014, 0x02DC, 0x2122, 0x0161, 0x203A, 0x0153, 0xFFFD, 0x017E, 0x0178};
  std::string out;
  out.reserve(text.size() + text.size() / 8);
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    const char32_t u = c < 0x80 ? c : c < 0xA0 ? kC1[c - 0x80] : c;
    if (u < 0x80) {
      out += static_cast<char>(u);
    } else if (u < 0x800) {
      out += static_cast<char>(0xC0 | (u >> 6));
      out += static_cast<char>(0x80 | (u & 0x3F));
    } else {
      out += static_cast<char>(0xE0 | (u >> 12));
      out += static_cast<char>(0x80 | ((u >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (u & 0x3F));
    }
  }
  return out;
}

std::string to_utf8_lossy(std::string_view text) {
  return is_valid_utf8(text) ? std::string(text) : windows1252_to_utf8(text);
}

std::string text_to_utf8(std::string_view text, std::string_view declared_encoding,
                         TextConversion& conversion) {
  const std::string declared = ascii_lower(declared_encoding);
  for (std::string_view latin1 : {"iso-8859-1", "iso8859-1", "latin1", "latin-1", "l1",
                                  "iso-8859-15", "windows-1252", "cp1252"}) {
    if (declared == latin1) {
      conversion = TextConversion::kDeclaredLatin1;
      return windows1252_to_utf8(text);
    }
  }
  if (is_valid_utf8(text)) {
    conversion = TextConversion::kNone;
    return std::string(text);
  }
  conversion = TextConversion::kUndeclaredLatin1;
  return windows1252_to_utf8(text);
}

}  // namespace sewerplan
