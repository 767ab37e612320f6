#include "mapped_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "pcsketch/core/error.h"

namespace pcsketch::io::detail {

MappedFile::MappedFile(const std::string& path) {
  const FileLoc where{path, {}, {}};
  // Every reader needs the whole file at once (counts are checked against its size): no streaming from stdin.
  if (path == "-") throw Error(where, "reading from standard input is not supported; name a file");
  // A FIFO, socket or device is refused before open(), which would block on a FIFO without a writer; O_NONBLOCK
  // and the second check cover a file swapped in between.
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) throw Error(where, "not a regular file");
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw Error(where, std::string("cannot open: ") + std::strerror(errno));
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw Error(where, "not a regular file");
  }
  size_ = static_cast<std::size_t>(st.st_size);
  if (size_ > 0) {
    void* p = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
    if (p == MAP_FAILED) {
      const int err = errno;
      ::close(fd);
      throw Error(where, std::string("cannot map into memory: ") + std::strerror(err));
    }
    // Readers go front to back once.
    ::madvise(p, size_, MADV_SEQUENTIAL);
    data_ = static_cast<const char*>(p);
  }
  ::close(fd);
}

MappedFile::~MappedFile() {
  if (data_ != nullptr) ::munmap(const_cast<char*>(data_), size_);
}

}  // namespace pcsketch::io::detail
