// Write to a temporary name, fsync, rename (docs/mesh-format.md "Writing").
//
// POSIX I/O rather than iostreams: the data must reach the disk (fsync) before the rename, or a
// crash right after it could leave an empty file under the final name on some file systems. The
// temporary sits in the target's folder so that rename() is atomic (no cross-device move); the
// pid keeps two processes writing the same target from sharing a temporary file.
#include "common/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "common/error.h"

namespace nmm {

void write_file_atomically(const std::string& path, const std::string& contents,
                           Durability durability) {
  const std::string tmp = path + ".tmp." + std::to_string(static_cast<long>(::getpid()));
  int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  auto fail = [&](int err) {
    if (fd >= 0) ::close(fd);
    ::unlink(tmp.c_str());
    throw WriteError(path, "", "cannot write: " + std::system_category().message(err));
  };
  if (fd < 0) fail(errno);
  const char* p = contents.data();
  std::size_t left = contents.size();
  while (left > 0) {
    const ssize_t w = ::write(fd, p, std::min<std::size_t>(left, std::size_t{1} << 30));
    if (w < 0) {
      if (errno == EINTR) continue;
      fail(errno);
    }
    if (w == 0) fail(EIO);  // no progress and no error: do not spin forever
    p += w;
    left -= static_cast<std::size_t>(w);
  }
  if (durability == Durability::synced && ::fsync(fd) != 0) fail(errno);
  const int closed = ::close(fd);
  fd = -1;  // closed even when close() reports an error
  if (closed != 0) fail(errno);
  if (::rename(tmp.c_str(), path.c_str()) != 0) fail(errno);
  if (durability == Durability::renamed) return;
  // Persist the rename itself. Best effort: the file is already complete under its name, so a
  // failure here is not reported as a failed write.
  const std::size_t slash = path.rfind('/');
  const std::string dir = slash == std::string::npos ? "."
                          : slash == 0               ? "/"
                                                     : path.substr(0, slash);
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    (void)::fsync(dfd);
    ::close(dfd);
  }
}

void prepare_output_folder(const std::string& dir) {
  {  // if this fails, the probe below names the problem
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
  }
  write_file_atomically(dir + "/.probe", "");
  std::remove((dir + "/.probe").c_str());
}

}  // namespace nmm
