#pragma once
// Outputs are written to a temporary file next to their target and renamed over it only when complete: a full disk
// or a failing writer never truncates, deletes or replaces the user's existing file. Every writer (draw's SVG, PDF,
// PNG and JSON, the PLY of features and sample, the lines JSON of features) goes through TempFile.

#include <filesystem>

namespace pcsketch {

/// The file `path` stands for once its symlinks are followed (`path` itself when it is no symlink): writing to
/// `-o link.png` replaces the file the link points to and keeps the link.
std::filesystem::path resolve_target(const std::filesystem::path& path);

/// Checks, before any work, that TempFile could replace `path`: an existing writable directory, and no directory,
/// device or FIFO in its place (after symlinks). @throws pcsketch::Error naming `path` and why.
void check_writable(const std::filesystem::path& path);

/// A new empty file in the directory of resolve_target(target), removed again unless commit() renames it over the
/// target. Its permissions are the target's when it exists, else the umask's.
class TempFile {
 public:
  /// @throws pcsketch::Error naming `target` if the target exists and is not a regular file (a rename would replace
  ///         a device or a directory's entry), or if the temporary file cannot be created.
  explicit TempFile(const std::filesystem::path& target);
  ~TempFile();
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  const std::filesystem::path& path() const { return temp_; }
  /// Renames the temporary file over the target. @throws pcsketch::Error if the rename fails.
  void commit();

 private:
  std::filesystem::path target_;  ///< as given, for messages
  std::filesystem::path final_;   ///< symlinks followed
  std::filesystem::path temp_;
  bool committed_ = false;
};

}  // namespace pcsketch
