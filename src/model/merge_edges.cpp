// Stage 7 of build_model: merge edges. An eliminated joint has no multiplier; its reaction is
// recovered by splitting the generalized force of the merged node (or rotation) between the
// bodies that share it (dynamics/reactions.cpp). For that, each merged group is a tree of edges
// rooted at its ground element (if any) or at its first element with an edge, one edge per
// eliminated joint, stored in post-order (children before parents).
#include "model/build_stages.hpp"

namespace mo2d::build {
namespace {

// One end of an edge: the body and body-local slot an element stands for.
struct End {
  int body = -1;  // -1: ground
  int slot = -1;  // local slot of x (node) or of the rotation
  bool ground = false;
};

struct Adj {
  int other, reaction;
  double sign_if_other_is_child;
};

struct Walk {
  const std::vector<End>& ends;
  const std::vector<std::vector<Adj>>& adj;
  bool rotation;
  std::vector<bool> visited;
  std::vector<MergeEdge>& edges;
};

// Depth-first from element e, appending edges in pre-order.
void visit(Walk& w, int e, int parent_edge) {
  w.visited[e] = true;
  std::vector<int> kids;
  for (const auto& a : w.adj[e]) {
    if (w.visited[a.other]) continue;
    MergeEdge me;
    me.parent_body = w.ends[e].body;
    me.child_body = w.ends[a.other].body;
    me.child_slot = w.ends[a.other].slot;
    me.rotation = w.rotation;
    me.reaction = a.reaction;
    me.sign = a.sign_if_other_is_child;
    w.edges.push_back(me);
    const int idx = static_cast<int>(w.edges.size()) - 1;
    visit(w, a.other, idx);
    kids.push_back(idx);
  }
  if (parent_edge >= 0) w.edges[parent_edge].child_edges = kids;
}

// Edges of the groups joined by `pairs` (element a, element b of each eliminated joint, whose
// reaction starts at column reactions[k]), appended to `edges` in post-order.
void add_edges(const std::vector<End>& ends, const std::vector<std::array<int, 2>>& pairs,
               const std::vector<int>& reactions, bool rotation, std::vector<MergeEdge>& edges) {
  const int n_elements = static_cast<int>(ends.size());
  std::vector<std::vector<Adj>> adj(n_elements);
  for (size_t k = 0; k < pairs.size(); ++k) {
    const auto [ea, eb] = pairs[k];
    adj[ea].push_back({eb, reactions[k], +1.0});  // eb child of ea: eb is body 2
    adj[eb].push_back({ea, reactions[k], -1.0});
  }
  std::vector<int> roots;
  for (int e = 0; e < n_elements; ++e)
    if (ends[e].ground && !adj[e].empty()) roots.push_back(e);
  for (int e = 0; e < n_elements; ++e)
    if (!ends[e].ground && !adj[e].empty()) roots.push_back(e);
  const size_t first = edges.size();
  Walk w{ends, adj, rotation, std::vector<bool>(n_elements, false), edges};
  for (int r : roots)
    if (!w.visited[r]) visit(w, r, -1);
  // reorder [first, end) into post-order (children first): reverse of pre-order works for a tree
  std::vector<MergeEdge> pre(edges.begin() + first, edges.end());
  const int count = static_cast<int>(pre.size());
  std::vector<int> newpos(count);
  for (int k = 0; k < count; ++k) newpos[k] = count - 1 - k;
  for (int k = 0; k < count; ++k) {
    MergeEdge e = pre[k];
    for (int& ce : e.child_edges) ce = static_cast<int>(first) + newpos[ce - first];
    edges[first + newpos[k]] = e;
  }
}

}  // namespace

void add_merge_edges(const Elements& el, const Reduced& red, const JointReactions& reactions,
                     Model& m) {
  // node groups: elements joined by eliminated revolute joints; reaction (Fx, Fy)
  std::vector<End> nodes(el.count());
  for (int e = 0; e < el.count(); ++e) nodes[e] = {el.body[e], 2 * el.local[e], el.body[e] < 0};
  std::vector<std::array<int, 2>> node_pairs;
  std::vector<int> node_reactions;
  for (size_t k = 0; k < red.revolutes.size(); ++k)
    if (red.revolute_merged[k]) {
      node_pairs.push_back(red.revolutes[k]);
      node_reactions.push_back(reactions.revolute[k]);
    }
  add_edges(nodes, node_pairs, node_reactions, false, m.merge_edges);

  // rotation groups: rotation elements joined by eliminated prismatic locks; reaction T
  const int NB = static_cast<int>(m.bodies.size());
  std::vector<End> rotations(NB + 1);
  for (int e = 0; e <= NB; ++e)
    rotations[e] = {e - 1, e == 0 ? -1 : m.bodies[e - 1].slots() - 1, e == 0};
  std::vector<std::array<int, 2>> rotation_pairs;
  std::vector<int> rotation_reactions;
  for (size_t k = 0; k < red.prismatics.size(); ++k)
    if (red.prismatics[k].merged) {
      rotation_pairs.push_back({red.prismatics[k].body1 + 1, red.prismatics[k].body2 + 1});
      rotation_reactions.push_back(reactions.prismatic[k]);
    }
  add_edges(rotations, rotation_pairs, rotation_reactions, true, m.merge_edges);
}

}  // namespace mo2d::build
