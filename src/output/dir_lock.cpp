// The lock of an output folder (output/dir_lock.hpp).
#include "output/dir_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "mo2d/error.hpp"
#include "output/write_file.hpp"

namespace mo2d::detail {

namespace {

// fd's file is the one `path` names now (not removed, nor replaced by another run's).
bool still_named(int fd, const std::string& path) {
  struct stat held {};
  struct stat named {};
  if (::fstat(fd, &held) != 0 || ::stat(path.c_str(), &named) != 0) return false;
  return held.st_dev == named.st_dev && held.st_ino == named.st_ino;
}

}  // namespace

DirLock::DirLock(const std::string& dir)
    : path_((std::filesystem::path(dir) / ".mo2d.lock").string()) {
  for (;;) {
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0)
      throw Error("cannot open the lock '" + path_ + "': " + std::strerror(errno), path_);
    int status = 0;
    while ((status = ::flock(fd_, LOCK_EX)) != 0 && errno == EINTR) {
    }
    if (status != 0) {
      const std::string why = std::strerror(errno);
      ::close(fd_);
      throw Error("cannot lock '" + path_ + "': " + why, path_);
    }
    if (still_named(fd_, path_)) break;
    ::close(fd_);  // the holder before us removed it: lock the file there now
  }
  slot_ = register_temporary(path_);
}

DirLock::~DirLock() {
  unregister_temporary(slot_);
  ::unlink(path_.c_str());  // while held: a waiter on this file will see it gone
  ::close(fd_);             // releases the lock
}

}  // namespace mo2d::detail
