// State-space export (mo2d/modes.hpp): each matrix as a labelled CSV, everything as one JSON
// document. Written by the caller through OutputSet or write_file_atomically (atomic).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "mo2d/error.hpp"
#include "mo2d/modes.hpp"

namespace mo2d {

namespace {

std::string num(double v, const char* what) {
  if (!std::isfinite(v))
    throw Error(std::string("state-space export: ") + what + " is not finite", what);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string csv_cell(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

struct Block {
  const MatrixXd* X;
  const std::vector<std::string>* rows;
  const std::vector<std::string>* cols;
  const char* name;
};

Block block_of(const StateSpace& ss, char matrix) {
  switch (matrix) {
    case 'G':
      return {&ss.G, &ss.states, &ss.states, "G"};
    case 'H':
      return {&ss.H, &ss.states, &ss.inputs, "H"};
    case 'C':
      return {&ss.C, &ss.outputs, &ss.states, "C"};
    case 'D':
      return {&ss.D, &ss.outputs, &ss.inputs, "D"};
    default:
      throw Error(std::string("state-space export: no matrix '") + matrix + "'");
  }
}

std::string labels_json(const std::vector<std::string>& l) {
  std::string s = "[";
  for (size_t i = 0; i < l.size(); ++i) s += (i ? ", " : "") + quoted(l[i]);
  return s + "]";
}

std::string matrix_json(const Block& b) {
  std::string s = "[";
  for (Eigen::Index i = 0; i < b.X->rows(); ++i) {
    s += i ? ",\n    [" : "\n    [";
    for (Eigen::Index j = 0; j < b.X->cols(); ++j) s += (j ? ", " : "") + num((*b.X)(i, j), b.name);
    s += "]";
  }
  return s + "]";
}

std::string vector_json(const std::vector<std::string>& labels, const VectorXd& v,
                        const char* what) {
  std::string s = "{";
  for (Eigen::Index i = 0; i < v.size(); ++i)
    s += (i ? ", " : "") + quoted(labels[i]) + ": " + num(v[i], what);
  return s + "}";
}

std::string modes_json(const StateSpace& ss, const std::vector<Mode>& modes) {
  std::ostringstream s;
  s << "[";
  for (size_t k = 0; k < modes.size(); ++k) {
    const Mode& md = modes[k];
    s << (k ? ",\n    " : "\n    ") << "{\"eigenvalue\": [" << num(md.eigenvalue.real(), "mode")
      << ", " << num(md.eigenvalue.imag(), "mode") << "], \"omega_n\": " << num(md.omega_n, "mode")
      << ", \"omega_d\": " << num(md.omega_d, "mode") << ", \"hz\": " << num(md.hz, "mode")
      << ", \"damping_ratio\": " << num(md.damping_ratio, "mode")
      << ", \"oscillatory\": " << (md.oscillatory ? "true" : "false")
      << ", \"rigid\": " << (md.rigid ? "true" : "false") << ", \"shape\": {";
    for (int i = 0; i < ss.p; ++i)
      s << (i ? ", " : "") << quoted(ss.states[i]) << ": " << num(md.dz[i], "mode shape");
    s << "}}";
  }
  s << "]";
  return s.str();
}

}  // namespace

std::string state_space_csv(const StateSpace& ss, char matrix) {
  const Block b = block_of(ss, matrix);
  std::string s = b.name;
  for (const auto& c : *b.cols) {
    s += ',';
    s += csv_cell(c);
  }
  s += "\n";
  for (Eigen::Index i = 0; i < b.X->rows(); ++i) {
    s += csv_cell((*b.rows)[i]);
    for (Eigen::Index j = 0; j < b.X->cols(); ++j) {
      s += ',';
      s += num((*b.X)(i, j), b.name);
    }
    s += "\n";
  }
  return s;
}

std::string state_space_json(const StateSpace& ss, const std::vector<Mode>& modes) {
  std::ostringstream s;
  s << "{\n  \"t\": " << num(ss.t, "t") << ",\n  \"states\": " << labels_json(ss.states)
    << ",\n  \"inputs\": " << labels_json(ss.inputs)
    << ",\n  \"outputs\": " << labels_json(ss.outputs);
  for (char c : {'G', 'H', 'C', 'D'}) {
    const Block b = block_of(ss, c);
    s << ",\n  \"" << b.name << "\": " << matrix_json(b);
  }
  s << ",\n  \"drift\": " << vector_json(ss.states, ss.drift, "drift")
    << ",\n  \"reference_efforts\": " << vector_json(ss.inputs, ss.u, "efforts")
    << ",\n  \"approximate\": " << quoted(ss.approximate)
    << ",\n  \"conditioning\": " << num(ss.conditioning, "conditioning")
    << ",\n  \"modes\": " << modes_json(ss, modes) << "\n}\n";
  return s.str();
}

namespace {

void check_same_labels(const std::vector<StateSpace>& along) {
  for (const StateSpace& ss : along)
    if (ss.states != along.front().states || ss.inputs != along.front().inputs ||
        ss.outputs != along.front().outputs)
      throw Error("state-space export along a reference: the labels at t = " + num(ss.t, "t") +
                      " differ from those at the first time (linearize_along keeps them fixed)",
                  "states", ss.t);
}

// The distinct notes of what was differenced, over all samples.
std::string approximate_notes(const std::vector<StateSpace>& along) {
  std::vector<std::string> notes;
  for (const StateSpace& ss : along)
    if (!ss.approximate.empty() &&
        std::find(notes.begin(), notes.end(), ss.approximate) == notes.end())
      notes.push_back(ss.approximate);
  std::string s;
  for (const auto& n : notes) s += (s.empty() ? "" : " | ") + n;
  return s;
}

}  // namespace

std::string state_space_along_csv(const std::vector<StateSpace>& along, char matrix) {
  if (along.empty()) throw Error("state-space export along a reference: no samples");
  check_same_labels(along);
  const Block first = block_of(along.front(), matrix);
  std::string s = std::string("t,") + first.name;
  // (s += ',') += x, not s += "," + x: GCC 12 warns falsely (-Wrestrict, its bug 105329) on the
  // latter in a unity build at -O3
  for (const auto& c : *first.cols) (s += ',') += csv_cell(c);
  s += "\n";
  for (const StateSpace& ss : along) {
    const Block b = block_of(ss, matrix);
    for (Eigen::Index i = 0; i < b.X->rows(); ++i) {
      s += num(ss.t, "t") + "," + csv_cell((*b.rows)[i]);
      for (Eigen::Index j = 0; j < b.X->cols(); ++j) (s += ',') += num((*b.X)(i, j), b.name);
      s += "\n";
    }
  }
  return s;
}

std::string state_space_along_json(const std::vector<StateSpace>& along) {
  if (along.empty()) throw Error("state-space export along a reference: no samples");
  check_same_labels(along);
  const StateSpace& f = along.front();
  std::ostringstream s;
  s << "{\n  \"states\": " << labels_json(f.states) << ",\n  \"inputs\": " << labels_json(f.inputs)
    << ",\n  \"outputs\": " << labels_json(f.outputs)
    << ",\n  \"approximate\": " << quoted(approximate_notes(along)) << ",\n  \"samples\": [";
  for (size_t k = 0; k < along.size(); ++k) {
    const StateSpace& ss = along[k];
    s << (k ? ",\n  {" : "\n  {") << "\"t\": " << num(ss.t, "t")
      << ", \"conditioning\": " << num(ss.conditioning, "conditioning") << ",\n   \"reference\": "
      << vector_json(ss.states, independent_state(ss, {ss.t, ss.q0, ss.q1}), "reference")
      << ",\n   \"reference_efforts\": " << vector_json(ss.inputs, ss.u, "efforts");
    for (char c : {'G', 'H', 'C', 'D'}) {
      const Block b = block_of(ss, c);
      s << ",\n   \"" << b.name << "\": " << matrix_json(b);
    }
    s << ",\n   \"drift\": " << vector_json(ss.states, ss.drift, "drift")
      << ",\n   \"modes\": " << modes_json(ss, vibration_modes(ss)) << "}";
  }
  s << "\n  ]\n}\n";
  return s.str();
}

}  // namespace mo2d
