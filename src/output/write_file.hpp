#pragma once
// Internal: writing one output file atomically, and the registry of temporaries behind it and
// behind OutputSet (mo2d/output.hpp). Used by mo2d (the CSV writers), mo2d_render (images, plots)
// and mo2d_box2d (the cross-check CSV): those targets have src/ as a private include directory.
#include <string>

namespace mo2d {

// Write `content` to `path` atomically: a hidden temporary DIR/.NAME.tmp.<pid>.<n> is written,
// flushed and renamed (removed if SIGINT/SIGTERM ends the process, remove_temporaries_on_signal).
// While an OutputSet::Scope is alive, the file is added to that set instead (mo2d/output.hpp).
void write_file_atomically(const std::string& path, const std::string& content);

namespace detail {
// Registry of temporary files to remove on a signal: a fixed table (the handler only unlinks).
// register_temporary returns a slot (-1 if the table is full: the file is then not cleaned).
int register_temporary(const std::string& path);
void unregister_temporary(int slot);
// DIR/.NAME.tmp.PID.N for path DIR/NAME.
std::string temporary_path(const std::string& path);
// Writes content to `tmp` (flushed and synced); throws Error naming `path`.
void write_temporary(const std::string& tmp, const std::string& path, const std::string& content);
}  // namespace detail

}  // namespace mo2d
