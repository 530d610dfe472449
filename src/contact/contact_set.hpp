#pragma once
// Internal to the contact stage (src/contact/): a contact compiled against a Model (its points
// resolved to body points), its gap at a state (dispatched to the kinds: point_line.hpp,
// circle_circle.hpp, profile.hpp), and the gradient of a function of a body point in the node
// coordinates.
#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

#include "mo2d/contact.hpp"
#include "mo2d/model.hpp"

namespace mo2d::detail {

// A contact with its points resolved: p the moving point; a, b the line's points (or a the
// circle's centre, the slot's ends, or the profile's centre and axis point). A slot is three of
// these (slot.hpp): `part` says which (-1: not a slot's part), `inside` whether the pin is in the
// slot (the run switches it). phi: a profile's last closest point (the next Newton's start; NaN:
// none yet).
struct CompiledContact {
  ContactDef def;
  BodyPoint p, a, b;
  int part = -1;
  bool inside = false;
  mutable double phi = NAN;
};

// Resolves c's point names against m (a named point, a body node "body.node", a ground node).
// Throws Error naming the contact and the unknown name, or a bad radius or law. A slot comes out
// whole (part -1: its gaps refused); compile_contacts gives its three parts.
CompiledContact compile_contact(const Model& m, const ContactDef& c);
// Appends c compiled to out: one contact, or a slot's three parts (slot.cpp).
void compile_contacts(const Model& m, const ContactDef& c, std::vector<CompiledContact>& out);

// The gap of c at (q0, q1) into out (out.J must have m.n1 entries; written, no allocation).
void gap_into(const Model& m, const CompiledContact& c, const Eigen::Ref<const Eigen::VectorXd>& q0,
              const Eigen::Ref<const Eigen::VectorXd>& q1, GapValue& out);
// The gap alone (m): what the events watch.
double gap_only(const Model& m, const CompiledContact& c,
                const Eigen::Ref<const Eigen::VectorXd>& q0);

// The tangent of c at (q0, q1) into out (out.J must have m.n1 entries; written, no allocation;
// contact_tangent.cpp, the maths in tangent.hpp).
void tangent_into(const Model& m, const CompiledContact& c,
                  const Eigen::Ref<const Eigen::VectorXd>& q0,
                  const Eigen::Ref<const Eigen::VectorXd>& q1, TangentValue& out);

// J += w^T dp/dq: the gradient of a function whose gradient with respect to the body point p is
// w, in the node coordinates (Example 2.6 (b): p = (1 - gamma) p_i + gamma p_j + rho z x (p_j -
// p_i), linear in the nodes). A point of the ground adds nothing.
void add_point_gradient(const Model& m, const BodyPoint& p, const Vec2& w, Eigen::VectorXd& J);

}  // namespace mo2d::detail
