#pragma once
// Internal: the exclusive lock of an output folder that OutputSet::commit holds while it renames a
// run's files in (mo2d/output.hpp), so that two runs writing to one folder at once leave the
// files of one run. It leaves nothing behind: the lock file DIR/.mo2d.lock exists only while a
// run holds it.
#include <string>

namespace mo2d::detail {

// Exclusive lock of DIR/.mo2d.lock (flock), held while alive; the file is removed when released.
// Removing a lock file others may be waiting on is safe because a lock counts only when, once
// taken, the path still names the file locked: a waiter that wakes on a removed (or replaced)
// file closes it and starts again. The path is registered with the signal handler's temporaries
// (write_file.hpp) while held, so an interrupted run removes it too.
class DirLock {
 public:
  explicit DirLock(const std::string& dir);  // blocks until held; throws Error naming the path
  ~DirLock();
  DirLock(const DirLock&) = delete;
  DirLock& operator=(const DirLock&) = delete;

 private:
  std::string path_;
  int fd_ = -1;
  int slot_ = -1;  // in the registry of temporaries
};

}  // namespace mo2d::detail
