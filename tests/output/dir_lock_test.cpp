// The lock of an output folder (src/output/dir_lock.hpp): exclusive among runs (threads here:
// flock locks belong to open files, so threads that open the lock file exclude each other as
// processes do), and gone from the folder once released.
#include "output/dir_lock.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

namespace mo2d {
namespace {

TEST(DirLock, ExclusiveAndLeavesNothing) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("mo2d_dir_lock_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::atomic<int> inside{0}, overlaps{0}, entries{0};
  std::vector<std::thread> threads;
  for (int k = 0; k < 4; ++k)
    threads.emplace_back([&] {
      for (int i = 0; i < 300; ++i) {
        detail::DirLock lock(dir.string());
        if (inside.fetch_add(1) != 0) overlaps.fetch_add(1);
        std::this_thread::yield();
        inside.fetch_sub(1);
        entries.fetch_add(1);
      }
    });
  for (auto& t : threads) t.join();
  EXPECT_EQ(entries.load(), 1200);
  // a waiter woken on a lock file its holder removed must not count it as held
  EXPECT_EQ(overlaps.load(), 0);
  EXPECT_TRUE(std::filesystem::is_empty(dir)) << "the lock file was left behind";
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace mo2d
