#pragma once
// A whole file mapped read-only into memory: one system call, no copy, pages loaded on demand.

#include <string>
#include <string_view>

namespace pcsketch::io::detail {

class MappedFile {
 public:
  /// @throws pcsketch::Error naming the path if it cannot be opened, is not a regular file, or cannot be mapped.
  explicit MappedFile(const std::string& path);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  std::string_view bytes() const { return {data_, size_}; }

 private:
  const char* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace pcsketch::io::detail
