#include "pcsketch/core/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <string>

#include "pcsketch/core/error.h"

namespace pcsketch {

namespace fs = std::filesystem;

namespace {
constexpr const char* kNotRegular = "exists and is not a regular file; it would not be replaced";
fs::path directory_of(const fs::path& file) { return file.has_parent_path() ? file.parent_path() : fs::path("."); }
}  // namespace

fs::path resolve_target(const fs::path& path) {
  fs::path p = path;
  std::error_code ec;
  // 40 links, as the kernel's own limit for path resolution: a loop ends here instead of spinning.
  for (int hops = 0; hops < 40 && fs::is_symlink(p, ec); ++hops) {
    const fs::path link = fs::read_symlink(p, ec);
    if (ec) break;
    p = link.is_absolute() ? link : p.parent_path() / link;
  }
  return p;
}

void check_writable(const fs::path& path) {
  const FileLoc where{path.string(), {}, {}};
  const fs::path target = resolve_target(path);
  std::error_code ec;
  const fs::file_status status = fs::status(target, ec);
  // ENOENT is the one error that lets a file be written (ENAMETOOLONG, ELOOP, EACCES do not).
  if (ec && status.type() != fs::file_type::not_found) throw Error(where, "cannot be written: " + ec.message());
  if (fs::exists(status) && !fs::is_regular_file(status))
    throw Error(where, kNotRegular);
  const fs::path dir = directory_of(target);
  if (!fs::is_directory(dir, ec)) throw Error(where, "the directory " + dir.string() + " does not exist");
  if (::access(dir.c_str(), W_OK) != 0) throw Error(where, "the directory " + dir.string() + " is not writable");
}

TempFile::TempFile(const fs::path& target) : target_(target), final_(resolve_target(target)) {
  static std::atomic<unsigned> counter{0};
  struct stat existing {};
  const bool exists = ::stat(final_.c_str(), &existing) == 0;
  // Renaming over a device or a FIFO (a symlink to /dev/full, as root) would replace it: never.
  if (exists && !S_ISREG(existing.st_mode))
    throw Error(FileLoc{target.string(), {}, {}}, kNotRegular);
  const fs::path dir = directory_of(final_);
  for (int attempt = 0; attempt < 100; ++attempt) {
    temp_ = dir /
            ("." + final_.filename().string() + ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    const int fd = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      if (exists) (void)::fchmod(fd, existing.st_mode & 07777);
      ::close(fd);
      return;
    }
    if (errno != EEXIST) break;
  }
  const std::string why = std::strerror(errno);
  temp_.clear();
  throw Error(FileLoc{target.string(), {}, {}}, "cannot create a file in " + dir.string() + ": " + why);
}

TempFile::~TempFile() {
  if (!committed_ && !temp_.empty()) ::unlink(temp_.c_str());
}

void TempFile::commit() {
  if (::rename(temp_.c_str(), final_.c_str()) != 0)
    throw Error(FileLoc{target_.string(), {}, {}}, std::string("cannot replace the file: ") + std::strerror(errno));
  committed_ = true;
}

}  // namespace pcsketch
