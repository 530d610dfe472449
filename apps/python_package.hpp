#pragma once
// Where this build's Python package mo2d is, and the interpreter it was built for (MO2D_PYTHON):
// used by `mo2d sweep` (cmd_sweep.cpp) and `mo2d doctor` (cmd_doctor.cpp).
#include <string>

namespace mo2d::cli {

// The python3 the package was built and tested with (/usr/bin/python3 on Debian), or "" when
// this mo2d was built without the package (MO2D_PYTHON=OFF).
std::string python_executable();

// The folder holding the package mo2d: installed beside this executable
// (BIN/../MO2D_PYTHON_INSTALL_DIR), else the build tree's (build/python); "" when neither exists
// (python3's own sys.path may still have it) or the package was not built.
std::string python_package_dir();

}  // namespace mo2d::cli
