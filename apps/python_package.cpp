// Where the Python package mo2d is (python_package.hpp).
#include "python_package.hpp"

#include <filesystem>
#include <system_error>

namespace mo2d::cli {

#ifdef MO2D_PYTHON_EXECUTABLE
std::string python_executable() {
  return MO2D_PYTHON_EXECUTABLE;
}

std::string python_package_dir() {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path().parent_path() / MO2D_PYTHON_INSTALL_DIR;
    if (fs::exists(installed / "mo2d" / "__init__.py", ec)) return installed.string();
  }
  if (fs::exists(fs::path(MO2D_PYTHON_BUILD_DIR) / "mo2d" / "__init__.py", ec))
    return MO2D_PYTHON_BUILD_DIR;
  return {};
}
#else
std::string python_executable() {
  return {};
}
std::string python_package_dir() {
  return {};
}
#endif

}  // namespace mo2d::cli
