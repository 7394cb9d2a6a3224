// SPDX-License-Identifier: MIT
#include "sewerplan/core/text_file.h"

#include <cerrno>
#include <cstring>
#include <string>

#include "sewerplan/core/ascii_case.h"

#include <fcntl.h>
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

}  // namespace

Result<std::string> read_text_file(const std::filesystem::path& path) {
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
