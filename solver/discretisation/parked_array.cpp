#include "solver/discretisation/parked_array.h"

#include <cerrno>
#include <cstdlib>
#include <string>

#include <fcntl.h>
#include <unistd.h>

#include "common/error.h"

namespace nmm::solve {

bool ParkingFile::write(const void* data, std::size_t bytes) {
  close();
  const char* dir = std::getenv("TMPDIR");
  std::string path = std::string(dir && *dir ? dir : "/tmp") + "/nmm-parked-XXXXXX";
  fd_ = mkstemp(path.data());
  if (fd_ < 0) return false;
  unlink(path.c_str());  // gone with the descriptor, whatever ends the process
  const char* p = static_cast<const char*>(data);
  std::size_t left = bytes;
  while (left > 0) {
    const ssize_t w = ::write(fd_, p, left);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) {  // a full disk: the array stays in memory
      close();
      return false;
    }
    p += w;
    left -= static_cast<std::size_t>(w);
  }
  bytes_ = bytes;
  return true;
}

void ParkingFile::read(void* data) {
  char* p = static_cast<char*>(data);
  std::size_t done = 0;
  while (done < bytes_) {
    const ssize_t r = pread(fd_, p + done, bytes_ - done, static_cast<off_t>(done));
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) {
      close();
      throw RunError("a parked array could not be read back from its temporary file (" + std::to_string(done) + " of " +
                     std::to_string(bytes_) + " bytes)");
    }
    done += static_cast<std::size_t>(r);
  }
  close();
}

void ParkingFile::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  bytes_ = 0;
}

}  // namespace nmm::solve
