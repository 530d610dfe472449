// CSV writing (labels in the header, 17 significant digits, atomic replace).
#include "mo2d/csv.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <atomic>
#include <sstream>

#include "mo2d/error.hpp"

namespace mo2d {

void write_file_atomically(const std::string& path, const std::string& content) {
  static std::atomic<unsigned> counter{0};
  const std::string tmp =
      path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw Error("cannot write '" + tmp + "': " + std::strerror(errno), path);
  const bool ok = std::fwrite(content.data(), 1, content.size(), f) == content.size() &&
                  std::fflush(f) == 0 && ::fsync(::fileno(f)) == 0;
  if (std::fclose(f) != 0 || !ok) {
    std::remove(tmp.c_str());
    throw Error("error while writing '" + tmp + "'", path);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::remove(tmp.c_str());
    throw Error("cannot rename '" + tmp + "' to '" + path + "': " + why, path);
  }
}

namespace {

// Columns shared by inverse and forward results: t, coordinates, quasi-velocities, their
// derivatives (label + ".dot"), efforts, reactions.
template <class Result>
void common_header(std::ostringstream& s, const Result& r) {
  s << "t";
  for (const auto& l : r.coordinate_labels) s << "," << l;
  for (const auto& l : r.rate_labels) s << "," << l;
  for (const auto& l : r.rate_labels) s << "," << l << ".dot";
  for (const auto& l : r.input_labels) s << "," << l;
  for (const auto& l : r.reaction_labels) s << "," << l;
}

template <class Result>
void common_row(std::ostringstream& s, const Result& r, int k) {
  s << r.time[k];
  for (int j = 0; j < r.q0.cols(); ++j) s << "," << r.q0(k, j);
  for (int j = 0; j < r.q1.cols(); ++j) s << "," << r.q1(k, j);
  for (int j = 0; j < r.a1.cols(); ++j) s << "," << r.a1(k, j);
  for (int j = 0; j < r.efforts.cols(); ++j) s << "," << r.efforts(k, j);
  for (int j = 0; j < r.reactions.cols(); ++j) s << "," << r.reactions(k, j);
}

}  // namespace

std::string inverse_csv(const InverseResult& r) {
  std::ostringstream s;
  s.precision(17);
  common_header(s, r);
  s << ",residual.position,residual.velocity,residual.acceleration\n";
  for (int k = 0; k < r.time.size(); ++k) {
    common_row(s, r, k);
    for (int j = 0; j < 3; ++j) s << "," << r.residuals(k, j);
    s << "\n";
  }
  return s.str();
}

std::string forward_csv(const ForwardResult& r) {
  std::ostringstream s;
  s.precision(17);
  common_header(s, r);
  s << ",energy.kinetic,energy.potential,work.inputs,energy.dissipated,work.loads,work.constraints";
  s << ",residual.position,residual.velocity\n";
  for (int k = 0; k < r.time.size(); ++k) {
    common_row(s, r, k);
    s << "," << r.kinetic[k] << "," << r.potential[k] << "," << r.input_work[k] << ","
      << r.dissipated[k] << "," << r.load_work[k] << "," << r.constraint_work[k] << ","
      << r.residuals(k, 0) << "," << r.residuals(k, 1) << "\n";
  }
  return s.str();
}

void write_forward_csv(const ForwardResult& r, const std::string& path) {
  write_file_atomically(path, forward_csv(r));
}

void write_inverse_csv(const InverseResult& r, const std::string& path) {
  write_file_atomically(path, inverse_csv(r));
}

}  // namespace mo2d
