#pragma once
// The output files of one run, written together or not at all.
//
// OutputSet::add() writes each file as a hidden temporary in its folder (DIR/.NAME.tmp.PID.N);
// commit() renames them all to their names under an exclusive lock of DIR/.mo2d.lock (flock; the
// file is removed when released), with SIGINT, SIGTERM and SIGHUP blocked while it renames. So:
//  - a run that fails before commit() leaves none of its files (the destructor removes the
//    temporaries, and the folder if the set created it and it is empty);
//  - an interrupted run leaves no temporary: remove_temporaries_on_signal() installs handlers that
//    remove every registered temporary and end the process by the same signal;
//  - two runs into one folder at once each land their whole set: the folder holds the files of one
//    run or of the other, never one run's CSV with the other's JSON.
// While an OutputSet::Scope is alive, every file mo2d writes (write_csv, the images and plots of
// mo2d::render, the cross-check's CSV) is added to that set instead of being renamed in at once.
#include <string>
#include <vector>

namespace mo2d {

// A set of output files written together or not at all (see the file's description).
class OutputSet {
 public:
  OutputSet() = default;
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;
  ~OutputSet();  // removes the temporaries of a set not committed

  // Writes `content` to a temporary next to `path` (its folder is created if needed). Throws Error.
  void add(const std::string& path, const std::string& content);
  // Renames every temporary added since the last commit to its path, under the folders' locks.
  // Throws Error (the files not yet renamed are removed by the destructor). Files may be added
  // after a commit (render: the frames land before ffmpeg reads them) and commit() called again.
  void commit();
  // The paths added so far, in order.
  std::vector<std::string> paths() const;

  // Routes the files mo2d writes to `set` while alive (one per thread; nested scopes stack).
  class Scope {
   public:
    // Routes mo2d's file writes of this thread to `set` until destroyed.
    explicit Scope(OutputSet& set);
    ~Scope();
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    OutputSet* previous_ = nullptr;
  };
  static OutputSet* active();  // of this thread, or nullptr

 private:
  struct File {
    std::string path, tmp;
    int slot = -1;      // in the signal-cleanup registry
    bool done = false;  // renamed in
  };
  std::vector<File> files_;
  std::vector<std::string> created_dirs_;
  bool committed_ = false;  // some file was renamed in (the folder is then kept)
  void discard();
};

// Install handlers of SIGINT, SIGTERM and SIGHUP (only where the disposition is the default) that
// remove the registered temporaries (of OutputSet and of every file being written) and then end the
// process by that signal (its exit status says so). Idempotent.
void remove_temporaries_on_signal();

}  // namespace mo2d
