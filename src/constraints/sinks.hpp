#pragma once
// Sinks of constraint entries (internal header): what position_rows / velocity_rows write into.
//   position level: add(row, q0 index, value);  velocity level: add(row, VarRef, value).
#include <vector>

#include "dynamics/reactions.hpp"
#include "mo2d/model.hpp"

namespace mo2d::detail {

struct DenseSink {  // position Jacobian (columns = q0 indices through colmap, -1 dropped)
  Eigen::Ref<Eigen::MatrixXd> J;
  const int* colmap = nullptr;
  void add(int row, int var, double v) {
    const int c = colmap ? colmap[var] : var;
    if (c >= 0) J(row, c) += v;
  }
};
struct DenseVelSink {  // velocity Jacobian A (columns = q1 indices)
  Eigen::Ref<Eigen::MatrixXd> A;
  void add(int row, const VarRef& ref, double v) {
    if (ref.var >= 0) A(row, ref.var) += v;
  }
};
struct SlotRecordSink {  // writes A and records the entries owned by body slots (reactions)
  Eigen::Ref<Eigen::MatrixXd> A;
  const Model& m;
  std::vector<SlotEntry>& entries;
  // inlined: called ~50 times per inverse sample, GCC kept it out of line (a call per entry)
  [[gnu::always_inline]] void add(int row, const VarRef& ref, double v) {
    if (ref.var >= 0) A(row, ref.var) += v;
    if (ref.body >= 0 && ref.slot >= 0)
      entries.push_back({row, m.bodies[ref.body].offset + ref.slot, v});
  }
};
struct NullSink {
  void add(int, int, double) {}
  void add(int, const VarRef&, double) {}
};

}  // namespace mo2d::detail
