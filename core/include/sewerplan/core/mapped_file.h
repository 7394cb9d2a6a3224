// SPDX-License-Identifier: MIT
// A regular file mapped read-only into memory, for the readers of large files: the map reader
// (map_io.cc) and the routing index's (domain/route_index.h: 270 MB at a million manholes).
//
// Internal to sewerplan's libraries (namespace detail). A 1,000,000-manhole map is 430 MB of JSON:
// read into a string, it was zeroed, then copied from the page cache, and every page of it faulted
// in on the way (a quarter of the whole plan's time, issue 16). Mapped, the reader reads the page
// cache's own pages, populated in one call. Only regular files of at least kMinMappedBytes are
// mapped (below that, mapping saves nothing measurable); everything else (a smaller file, a pipe, a
// system without mmap) is read as before by read_text_file. A mapped file truncated by another
// process while it is read would fault the reader (SIGBUS), the same caveat as every mmap-based
// reader's: map files that are not being written (sewerplan's own writers replace a file by
// renaming, which is safe).
//
//   if (std::optional<MappedFile> file = MappedFile::open(path)) parse(file->text());
//
// Thread safety: a value; text() may be read from any thread while the object lives.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string_view>

namespace sewerplan::detail {

class MappedFile {
 public:
  static constexpr std::size_t kMinMappedBytes = std::size_t{64} << 20;  // 64 MiB

  // Empty if the file is not a non-empty regular file of at least min_bytes, or cannot be mapped.
  static std::optional<MappedFile> open(const std::filesystem::path& path,
                                        std::size_t min_bytes = kMinMappedBytes);

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
