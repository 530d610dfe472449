// Output files of one run, written together or not at all (mo2d/output.hpp).
#include "mo2d/output.hpp"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <thread>

#include "mo2d/error.hpp"
#include "output/dir_lock.hpp"
#include "output/write_file.hpp"

namespace mo2d {

namespace {

// ---- temporaries to remove on a signal --------------------------------------------------------
// A fixed table in static storage: the handler reads it without locks or allocation (states are
// lock-free atomics: 0 free, 1 being filled, 2 a path to remove).
constexpr int kSlots = 1024;
constexpr std::size_t kPathMax = 4096;
struct Slot {
  std::atomic<int> state{0};
  char path[kPathMax]{};  // zero: the table is constant-initialized (bss)
};
constinit Slot g_slots[kSlots];  // zero-initialized bss: no page is touched at start-up
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void remove_temporaries_and_die(int sig) {
  for (auto& s : g_slots)
    if (s.state.load() == 2) ::unlink(s.path);  // async-signal-safe
  std::signal(sig, SIG_DFL);
  std::raise(sig);  // blocked while in the handler: delivered when it returns
}

// ---- test hooks (tests/CMakeLists.txt): deterministic interleavings and interruptions ----------
// MO2D_TEST_OUTPUT_DELAY="A,B": sleep A s before the first file of a set, B s after each file.
// MO2D_TEST_OUTPUT_SIGNAL=N: raise signal N once the first temporary is written.
void test_sleep(int which) {
  const char* env = std::getenv("MO2D_TEST_OUTPUT_DELAY");
  if (!env) return;
  double a = 0, b = 0;
  if (std::sscanf(env, "%lf,%lf", &a, &b) < 1) return;
  const double s = which == 0 ? a : b;
  if (s > 0) std::this_thread::sleep_for(std::chrono::duration<double>(s));
}
void test_signal() {
  if (const char* env = std::getenv("MO2D_TEST_OUTPUT_SIGNAL")) std::raise(std::atoi(env));
}

thread_local OutputSet* t_active = nullptr;

// Blocks the termination signals while alive (an interrupt comes before or after, not amid).
class BlockSignals {
 public:
  BlockSignals() {
    sigset_t s;
    sigemptyset(&s);
    sigaddset(&s, SIGINT);
    sigaddset(&s, SIGTERM);
    sigaddset(&s, SIGHUP);
    pthread_sigmask(SIG_BLOCK, &s, &old_);
  }
  ~BlockSignals() { pthread_sigmask(SIG_SETMASK, &old_, nullptr); }
  BlockSignals(const BlockSignals&) = delete;
  BlockSignals& operator=(const BlockSignals&) = delete;

 private:
  sigset_t old_;
};

std::string folder_of(const std::string& path) {
  const auto p = std::filesystem::path(path).parent_path();
  return p.empty() ? std::string(".") : p.string();
}

}  // namespace

namespace detail {

int register_temporary(const std::string& path) {
  if (path.size() >= kPathMax) return -1;
  for (int k = 0; k < kSlots; ++k) {
    int expected = 0;
    if (g_slots[k].state.compare_exchange_strong(expected, 1)) {
      std::memcpy(g_slots[k].path, path.c_str(), path.size() + 1);
      g_slots[k].state.store(2);
      return k;
    }
  }
  return -1;
}

void unregister_temporary(int slot) {
  if (slot >= 0 && slot < kSlots) g_slots[slot].state.store(0);
}

std::string temporary_path(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  const std::filesystem::path p(path);
  std::string name = ".";  // (appends: GCC 12 warns falsely on "." + std::string, -Wrestrict)
  name += p.filename().string();
  name += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  return (p.parent_path() / name).string();
}

void write_temporary(const std::string& tmp, const std::string& path, const std::string& content) {
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw Error("cannot write '" + tmp + "': " + std::strerror(errno), path);
  const bool ok = std::fwrite(content.data(), 1, content.size(), f) == content.size() &&
                  std::fflush(f) == 0 && ::fsync(::fileno(f)) == 0;
  if (std::fclose(f) != 0 || !ok) {
    std::remove(tmp.c_str());
    throw Error("error while writing '" + tmp + "'", path);
  }
}

}  // namespace detail

void write_file_atomically(const std::string& path, const std::string& content) {
  if (OutputSet* set = OutputSet::active()) return set->add(path, content);
  const std::string tmp = detail::temporary_path(path);
  const int slot = detail::register_temporary(tmp);  // removed if a signal ends the process
  try {
    detail::write_temporary(tmp, path, content);
  } catch (...) {
    detail::unregister_temporary(slot);
    throw;
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::remove(tmp.c_str());
    detail::unregister_temporary(slot);
    throw Error("cannot rename '" + tmp + "' to '" + path + "': " + why, path);
  }
  detail::unregister_temporary(slot);
}

void remove_temporaries_on_signal() {
  static std::atomic<bool> installed{false};
  if (installed.exchange(true)) return;
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old {};
    sigaction(sig, nullptr, &old);
    if (old.sa_handler != SIG_DFL) continue;  // ignored (a background job) or someone else's
    struct sigaction sa {};
    sa.sa_handler = remove_temporaries_and_die;
    sigemptyset(&sa.sa_mask);
    sigaction(sig, &sa, nullptr);
  }
}

OutputSet::~OutputSet() {
  if (t_active == this) t_active = nullptr;
  discard();
}

void OutputSet::discard() {
  for (auto& f : files_) {
    if (!f.done) std::remove(f.tmp.c_str());
    detail::unregister_temporary(f.slot);
    f.slot = -1;
  }
  if (!committed_) {
    std::error_code ec;
    for (auto it = created_dirs_.rbegin(); it != created_dirs_.rend(); ++it)
      if (std::filesystem::is_empty(*it, ec)) std::filesystem::remove(*it, ec);
  }
  files_.clear();
  created_dirs_.clear();
}

void OutputSet::add(const std::string& path, const std::string& content) {
  if (files_.empty()) test_sleep(0);
  const std::string dir = folder_of(path);
  std::error_code ec;
  if (!std::filesystem::exists(dir, ec)) {
    // remember the folders this set creates (outermost first), to remove them if it fails
    std::vector<std::string> missing;
    for (auto p = std::filesystem::path(dir); !p.empty() && !std::filesystem::exists(p, ec);
         p = p.parent_path())
      missing.insert(missing.begin(), p.string());
    std::filesystem::create_directories(dir, ec);
    if (ec) throw Error("cannot create the folder '" + dir + "': " + ec.message(), dir);
    created_dirs_.insert(created_dirs_.end(), missing.begin(), missing.end());
  }
  File f{path, detail::temporary_path(path), -1, false};
  f.slot = detail::register_temporary(f.tmp);  // before the file exists: no window uncovered
  files_.push_back(f);
  detail::write_temporary(f.tmp, path, content);
  if (files_.size() == 1) test_signal();
  test_sleep(1);
}

void OutputSet::commit() {
  std::vector<std::string> dirs;
  for (const auto& f : files_) {
    if (f.done) continue;
    std::error_code ec;
    if (std::filesystem::is_directory(f.path, ec))  // rename() would fail on it: fail before any
      throw Error("cannot write '" + f.path + "': it is a folder", f.path);
    const std::string d = folder_of(f.path);
    if (std::find(dirs.begin(), dirs.end(), d) == dirs.end()) dirs.push_back(d);
  }
  if (dirs.empty()) return;
  std::sort(dirs.begin(), dirs.end());  // one lock order for every run: no deadlock
  std::vector<std::unique_ptr<detail::DirLock>> locks;
  locks.reserve(dirs.size());
  for (const auto& d : dirs) locks.push_back(std::make_unique<detail::DirLock>(d));
  BlockSignals blocked;
  std::vector<File*> renamed;
  for (auto& f : files_) {
    if (f.done) continue;
    if (std::rename(f.tmp.c_str(), f.path.c_str()) != 0) {
      // not a partial set: the files this commit renamed in are removed too (the temporaries
      // left are removed by discard())
      const std::string why = std::strerror(errno);
      for (File* r : renamed) {
        std::remove(r->path.c_str());
        r->done = false;
      }
      throw Error("cannot rename '" + f.tmp + "' to '" + f.path + "': " + why, f.path);
    }
    f.done = true;
    renamed.push_back(&f);
  }
  committed_ = true;
  for (File* f : renamed) {
    detail::unregister_temporary(f->slot);
    f->slot = -1;
  }
}

std::vector<std::string> OutputSet::paths() const {
  std::vector<std::string> out;
  for (const auto& f : files_) out.push_back(f.path);
  return out;
}

OutputSet::Scope::Scope(OutputSet& set) : previous_(t_active) {
  t_active = &set;
}
OutputSet::Scope::~Scope() {
  t_active = previous_;
}
OutputSet* OutputSet::active() {
  return t_active;
}

}  // namespace mo2d
