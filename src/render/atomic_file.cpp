#include "render/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <string>

#include "pcsketch/core/error.h"

namespace pcsketch::render::detail {

namespace fs = std::filesystem;

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

TempFile::TempFile(const fs::path& target) : target_(target), final_(resolve_target(target)) {
  static std::atomic<unsigned> counter{0};
  struct stat existing {};
  const bool exists = ::stat(final_.c_str(), &existing) == 0;
  const fs::path dir = final_.has_parent_path() ? final_.parent_path() : fs::path(".");
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

}  // namespace pcsketch::render::detail
