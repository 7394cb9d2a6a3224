// SPDX-License-Identifier: MIT
#include "sewerplan/core/text_file.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <optional>
#include <string>
#include <utility>

#include "sewerplan/core/ascii_case.h"
#include "sewerplan/core/check.h"

#include <fcntl.h>
#include <iconv.h>
#include <sys/stat.h>
#include <unistd.h>

namespace sewerplan {

namespace {

Error read_error(const std::filesystem::path& path, const std::string& why) {
  return Error{ErrorCode::kIo, "cannot read " + path.string() + ": " + why};
}

const char* file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "it is a directory";
  if (S_ISCHR(mode)) return "it is a character device, not a file";
  if (S_ISBLK(mode)) return "it is a block device, not a file";
  if (S_ISSOCK(mode)) return "it is a socket, not a file";
  return "it is not a regular file";
}

Result<std::string> read_bytes(const std::filesystem::path& path) {
  // Opened without blocking: a FIFO that nobody writes to would block open() forever.
  int fd = -1;
  do {
    fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  } while (fd < 0 && errno == EINTR);
  if (fd < 0) return read_error(path, std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) return read_error(path, std::strerror(errno));
  const bool fifo = S_ISFIFO(st.st_mode);
  // A device (/dev/zero, a terminal) or a socket may never end: refused. A pipe (a shell's
  // `<(...)`, a FIFO with a writer) is read to its end.
  if (!S_ISREG(st.st_mode) && !fifo) return read_error(path, file_kind(st.st_mode));
  if (::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK) != 0) {
    return read_error(path, std::strerror(errno));
  }
  // A regular file is read at once into a string of its size (a 430 MB map is not grown and
  // copied); it may have grown since, so reading goes on to the end.
  std::string text;
  text.resize(S_ISREG(st.st_mode) ? static_cast<std::size_t>(st.st_size) + 1 : 64 * 1024);
  std::size_t got = 0;
  while (true) {
    if (got == text.size()) text.resize(text.size() * 2);
    const ssize_t n = ::read(fd, text.data() + got, text.size() - got);
    if (n < 0) {
      if (errno == EINTR) continue;
      return read_error(path, std::strerror(errno));
    }
    if (n == 0) break;
    got += static_cast<std::size_t>(n);
  }
  text.resize(got);
  if (fifo && got == 0) {
    return read_error(path, "it is a FIFO (named pipe) and nothing was written to it");
  }
  return text;
}

}  // namespace

Result<std::string> read_text_file(const std::filesystem::path& path) {
  Result<std::string> bytes = read_bytes(path);
  if (!bytes.has_value()) return bytes;
  if (byte_order_mark(*bytes).size == 0) return bytes;
  return without_byte_order_mark(*bytes, path.string());
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

namespace {

// Code units of an encoding: where iconv meets a byte sequence that is no character, decoding
// goes on this many bytes later.
std::size_t unit_size(std::string_view encoding) {
  const std::string e = ascii_lower(encoding);
  if (e.starts_with("utf-32") || e.starts_with("ucs-4")) return 4;
  if (e.starts_with("utf-16") || e.starts_with("ucs-2")) return 2;
  return 1;
}

// What decode() did.
struct Decoded {
  std::string text;
  std::size_t replaced = 0;           // bytes that are no character: U+FFFD each unit
  std::size_t first_replaced_at = 0;  // the byte offset of the first
};

// `text` in `encoding`, decoded to UTF-8 with iconv; none if iconv does not know the encoding.
// Bytes that are no character in it become U+FFFD, counted.
std::optional<Decoded> decode(std::string_view text, std::string_view encoding) {
  iconv_t cd = iconv_open("UTF-8", std::string(encoding).c_str());
  if (cd == reinterpret_cast<iconv_t>(-1)) return std::nullopt;
  const std::size_t unit = unit_size(encoding);
  Decoded out;
  out.text.resize(text.size() + text.size() / 2 + 16);
  // iconv's interface takes char* for its input, which it does not change.
  char* in = const_cast<char*>(text.data());  // NOLINT(cppcoreguidelines-pro-type-const-cast)
  std::size_t in_left = text.size();
  std::size_t used = 0;
  while (in_left > 0) {
    char* to = out.text.data() + used;
    std::size_t to_left = out.text.size() - used;
    const std::size_t done = iconv(cd, &in, &in_left, &to, &to_left);
    used = out.text.size() - to_left;
    if (done != static_cast<std::size_t>(-1)) break;
    if (errno == E2BIG) {
      out.text.resize(out.text.size() * 2);
      continue;
    }
    // EILSEQ (no character here) or EINVAL (cut off at the end): U+FFFD, and on.
    if (out.replaced++ == 0) out.first_replaced_at = text.size() - in_left;
    const std::size_t skip = std::min(unit, in_left);
    in += skip;
    in_left -= skip;
    out.text.resize(std::max(out.text.size(), used + 3));
    out.text.replace(used, 3, "\xEF\xBF\xBD");
    used += 3;
    iconv(cd, nullptr, nullptr, nullptr, nullptr);  // back to the initial shift state
  }
  iconv_close(cd);
  out.text.resize(used);
  return out;
}

// Undeclared UTF-16: the first characters of a sewer file (a '<', '[', '{', a letter) are ASCII,
// which UTF-16 writes with a NUL byte beside each.
std::string_view undeclared_utf16(std::string_view text) {
  if (text.size() < 4) return {};
  if (text[0] != '\0' && text[1] == '\0' && text[2] != '\0' && text[3] == '\0') return "UTF-16LE";
  if (text[0] == '\0' && text[1] != '\0' && text[2] == '\0' && text[3] != '\0') return "UTF-16BE";
  return {};
}

}  // namespace

std::string windows1252_to_utf8(std::string_view text) {
  std::optional<Decoded> decoded = decode(text, "WINDOWS-1252");
  SEWER_CHECK(decoded.has_value(), "iconv has no Windows-1252");
  return std::move(decoded->text);
}

std::string to_utf8_lossy(std::string_view text) {
  return is_valid_utf8(text) ? std::string(text) : windows1252_to_utf8(text);
}

ByteOrderMark byte_order_mark(std::string_view text) {
  // UTF-32LE's mark begins as UTF-16LE's: look at it first.
  static constexpr std::array<std::pair<std::string_view, std::string_view>, 5> kMarks{{
      {"\xEF\xBB\xBF", "UTF-8"},
      {std::string_view("\xFF\xFE\0\0", 4), "UTF-32LE"},
      {std::string_view("\0\0\xFE\xFF", 4), "UTF-32BE"},
      {"\xFF\xFE", "UTF-16LE"},
      {"\xFE\xFF", "UTF-16BE"},
  }};
  for (const auto& [mark, encoding] : kMarks) {
    if (text.starts_with(mark)) return {.encoding = encoding, .size = mark.size()};
  }
  return {};
}

Result<std::string> without_byte_order_mark(std::string_view text, const std::string& file) {
  const ByteOrderMark mark = byte_order_mark(text);
  text.remove_prefix(mark.size);
  if (mark.size == 0 || mark.encoding == "UTF-8") return std::string(text);
  std::optional<Decoded> decoded = decode(text, mark.encoding);
  SEWER_CHECK(decoded.has_value(), "iconv has no UTF-16 or UTF-32");
  if (decoded->replaced > 0) {
    return Error{ErrorCode::kParse,
                 file + ": begins with the byte-order mark of " + std::string(mark.encoding) +
                     " but is not " + std::string(mark.encoding) + " at byte " +
                     std::to_string(decoded->first_replaced_at + mark.size) +
                     (decoded->replaced > 1
                          ? " (and " + std::to_string(decoded->replaced - 1) + " more places)"
                          : std::string())};
  }
  return std::move(decoded->text);
}

Result<std::string> text_to_utf8(std::string_view text, std::string_view declared_encoding,
                                 const std::string& file, TextDecoding& how) {
  how = TextDecoding{.declared = std::string(declared_encoding)};
  std::string encoding;
  if (const ByteOrderMark mark = byte_order_mark(text); mark.size > 0) {
    text.remove_prefix(mark.size);
    encoding = mark.encoding;
    how.conversion = TextConversion::kDeclared;
  } else if (!declared_encoding.empty()) {
    const std::string declared = ascii_lower(declared_encoding);
    encoding = declared_encoding;
    how.conversion = TextConversion::kDeclared;
    if (declared == "iso-8859-1" || declared == "iso8859-1" || declared == "iso_8859-1" ||
        declared == "latin1" || declared == "latin-1" || declared == "l1") {
      encoding = "WINDOWS-1252";
    } else if (declared.starts_with("utf-16") || declared.starts_with("utf-32")) {
      // Declared so, but its first bytes are single-byte ASCII: decoded before (read_text_file
      // decodes a UTF-16 file with a byte-order mark), or never UTF-16; UTF-8 as it is.
      if (!text.empty() && text.front() != '\0' && (text.size() < 2 || text[1] != '\0'))
        encoding = "UTF-8";
    }
  }
  if (encoding.empty()) {
    // UTF-16's NUL bytes are valid UTF-8: look for them first.
    const std::string_view utf16 = undeclared_utf16(text);
    if (utf16.empty() && is_valid_utf8(text)) {
      how.encoding = "UTF-8";
      return std::string(text);
    }
    encoding = utf16.empty() ? "WINDOWS-1252" : utf16;
    how.conversion = TextConversion::kAssumed;
  }
  const std::string lower = ascii_lower(encoding);
  if (lower == "utf-8" || lower == "utf8" || lower == "us-ascii" || lower == "ascii") {
    if (is_valid_utf8(text)) {
      how.conversion = TextConversion::kNone;
      how.encoding = "UTF-8";
      return std::string(text);
    }
    // Declared UTF-8 but is not: the usual mislabelled Windows-1252 export.
    encoding = "WINDOWS-1252";
    how.conversion = TextConversion::kAssumed;
  }
  std::optional<Decoded> decoded = decode(text, encoding);
  if (!decoded) {
    return Error{ErrorCode::kUnsupportedFormat,
                 file + ": declares the text encoding '" + to_utf8_lossy(declared_encoding) +
                     "', which sewerplan does not know (iconv has no such encoding): save the "
                     "file in UTF-8, or declare its encoding by a name iconv knows "
                     "(ISO-8859-15, WINDOWS-1250, ...)"};
  }
  how.encoding = encoding;
  how.replaced = decoded->replaced;
  return std::move(decoded->text);
}

Result<std::string> utf8_to_text(std::string_view utf8, std::string_view encoding,
                                 const std::string& file) {
  const std::string lower = ascii_lower(encoding);
  if (lower == "utf-8" || lower == "utf8") return std::string(utf8);
  iconv_t cd = iconv_open(std::string(encoding).c_str(), "UTF-8");
  if (cd == reinterpret_cast<iconv_t>(-1)) {
    return Error{ErrorCode::kUnsupportedFormat, file + ": cannot write text in " +
                                                    to_utf8_lossy(encoding) +
                                                    " (iconv has no such encoding)"};
  }
  std::string out(utf8.size() * 4 + 16, '\0');
  // iconv's interface takes char* for its input, which it does not change.
  char* in = const_cast<char*>(utf8.data());  // NOLINT(cppcoreguidelines-pro-type-const-cast)
  std::size_t in_left = utf8.size();
  char* to = out.data();
  std::size_t to_left = out.size();
  const std::size_t done = iconv(cd, &in, &in_left, &to, &to_left);
  if (done != static_cast<std::size_t>(-1)) iconv(cd, nullptr, nullptr, &to, &to_left);
  iconv_close(cd);
  if (done == static_cast<std::size_t>(-1)) {
    const std::size_t at = utf8.size() - in_left;
    return Error{ErrorCode::kUnsupportedFormat,
                 file + ": the text at byte " + std::to_string(at) + " of its UTF-8 (\"" +
                     std::string(utf8.substr(at, 8)) + "...\") has no character in " +
                     std::string(encoding)};
  }
  out.resize(out.size() - to_left);
  return out;
}

void warn_about_decoding(const TextDecoding& how, const std::string& file,
                         Diagnostics& diagnostics) {
  const std::string as = how.encoding == "WINDOWS-1252" ? "Windows-1252 (Latin-1)" : how.encoding;
  if (how.conversion == TextConversion::kAssumed) {
    diagnostics.warning(
        file, how.declared.empty()
                  ? "not UTF-8, and no encoding declared: read as " + as
                  : "declared " + to_utf8_lossy(how.declared) + " but is not: read as " + as);
  }
  if (how.replaced > 0) {
    diagnostics.warning(file, std::to_string(how.replaced) + " bytes are no character in " + as +
                                  ": read as U+FFFD");
  }
}

}  // namespace sewerplan
