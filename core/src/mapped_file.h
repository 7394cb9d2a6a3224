// SPDX-License-Identifier: MIT
// A regular file mapped read-only into memory, for the map reader (map_io.cc).
//
// Private to core. A 1,000,000-manhole map is 430 MB of JSON: read into a string, it was zeroed,
// then copied from the page cache, and every page of it faulted in on the way (a quarter of the
// whole plan's time, issue 16). Mapped, the reader reads the page cache's own pages, populated in
// one call. Only regular files are mapped; everything else (a pipe, an empty file, a system
// without mmap) is read as before by read_text_file. A file truncated by another process while it
// is mapped would fault the reader: map files that are not being written.
//
//   if (std::optional<MappedFile> file = MappedFile::open(path)) parse(file->text());
//
// Thread safety: a value; text() may be read from any thread while the object lives.
#pragma once

#include <filesystem>
#include <optional>
#include <string_view>

namespace sewerplan::detail {

class MappedFile {
 public:
  // Empty if the file is not a non-empty regular file or cannot be mapped.
  static std::optional<MappedFile> open(const std::filesystem::path& path);

  MappedFile(MappedFile&& other) noexcept;
  MappedFile& operator=(MappedFile&& other) noexcept;
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  ~MappedFile();

  std::string_view text() const { return {data_, size_}; }
  void close();  // unmaps; text() is empty afterwards

 private:
  MappedFile(const char* data, std::size_t size) : data_(data), size_(size) {}

  const char* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace sewerplan::detail
