// No heap allocation inside the per-sample inverse-dynamics loop (InverseData is the workspace:
// everything inverse_dynamics_sample() needs is allocated when it is constructed).
//
// How allocations are counted. This file replaces the global operator new/delete (all the usual
// overloads: plain, array, nothrow, aligned, sized delete) for the whole mo2d_tests binary. The
// replacements forward to malloc/free and only count while `counting` is set, i.e. inside a
// CountAllocations scope, so every other test is unaffected. Eigen does not use operator new: it
// allocates with std::malloc. To see those allocations too, malloc/calloc/realloc are counted
// at the C level as well:
//   - plain build (glibc): malloc, calloc and realloc are interposed here and forward to glibc's
//     __libc_malloc/__libc_calloc/__libc_realloc (same heap, so glibc's free is unchanged);
//   - AddressSanitizer build: ASan owns malloc, so instead of interposing it we register
//     __sanitizer_install_malloc_and_free_hooks, called by ASan on every allocation. ASan still
//     checks all memory (our operator new allocates through ASan's malloc); what is lost is
//     only its new/delete vs malloc/free mismatch report for this binary.
// While counting, the call stack of the first few allocations is recorded and printed (raw
// frames; run `addr2line -f -C -e <binary> <offset>` or a RelWithDebInfo build under gdb with
// `break mo2d_count_allocation` to resolve them).
#include <execinfo.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Core>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <new>
#include <numbers>
#include <sstream>

#include "contact/contact_forces.hpp"
#include "contact/slot_set.hpp"
#include "mo2d/contact.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/forward_data.hpp"
#include "mo2d/inverse.hpp"
#include "mo2d/mechanisms.hpp"
#include "mo2d/model.hpp"
#include "mo2d/scene.hpp"
#include "mo2d/scene_sensitivity.hpp"
#include "mo2d/sensitivity.hpp"

#if defined(__SANITIZE_ADDRESS__)
#define MO2D_ALLOC_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MO2D_ALLOC_TEST_ASAN 1
#endif
#endif

// ---- counters -----------------------------------------------------------------------------------
namespace {

std::atomic<bool> counting{false};
std::atomic<long> new_count{0};     // operator new calls
std::atomic<long> malloc_count{0};  // malloc/calloc/realloc (incl. those made by operator new)

constexpr int kMaxTraces = 12, kMaxFrames = 32;
void* traces[kMaxTraces][kMaxFrames];
int trace_depth[kMaxTraces];
std::atomic<int> n_traces{0};
thread_local bool in_hook = false;  // backtrace() may allocate itself

}  // namespace

// Called for every counted allocation; extern "C" so a debugger can break on it.
extern "C" __attribute__((noinline)) void mo2d_count_allocation(std::atomic<long>& counter) {
  counter.fetch_add(1, std::memory_order_relaxed);
  if (in_hook) return;
  in_hook = true;
  const int k = n_traces.load(std::memory_order_relaxed);
  if (k < kMaxTraces) {
    n_traces.store(k + 1, std::memory_order_relaxed);
    trace_depth[k] = backtrace(traces[k], kMaxFrames);
  }
  in_hook = false;
}

namespace {

inline void count_new() {
  if (counting.load(std::memory_order_relaxed)) mo2d_count_allocation(new_count);
}
inline void count_malloc() {
  if (counting.load(std::memory_order_relaxed)) mo2d_count_allocation(malloc_count);
}

}  // namespace

// ---- C-level allocation counting ----------------------------------------------------------------
#if defined(MO2D_ALLOC_TEST_ASAN)
extern "C" int __sanitizer_install_malloc_and_free_hooks(void (*malloc_hook)(const volatile void*,
                                                                             std::size_t),
                                                         void (*free_hook)(const volatile void*));
namespace {
void asan_malloc_hook(const volatile void*, std::size_t) {
  count_malloc();
}
void asan_free_hook(const volatile void*) {}
const bool hooks_installed =
    __sanitizer_install_malloc_and_free_hooks(asan_malloc_hook, asan_free_hook) != 0;
}  // namespace
#elif defined(__GLIBC__)
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* malloc(std::size_t n) {
  count_malloc();
  return __libc_malloc(n);
}
void* calloc(std::size_t n, std::size_t s) {
  count_malloc();
  return __libc_calloc(n, s);
}
void* realloc(void* p, std::size_t n) {
  count_malloc();
  return __libc_realloc(p, n);
}
}
namespace {
const bool hooks_installed = true;
}
#else
namespace {
const bool hooks_installed = false;  // only operator new is counted
}
#endif

// ---- replaced global operator new / delete ------------------------------------------------------
namespace {

void* allocate(std::size_t n) {
  count_new();
  if (n == 0) n = 1;
  for (;;) {
    if (void* p = std::malloc(n)) return p;
    std::new_handler h = std::get_new_handler();
    if (!h) throw std::bad_alloc();
    h();
  }
}

void* allocate(std::size_t n, std::align_val_t al) {
  count_new();
  std::size_t a = static_cast<std::size_t>(al);
  if (a < sizeof(void*)) a = sizeof(void*);
  if (n == 0) n = 1;
  for (;;) {
    void* p = nullptr;
    if (posix_memalign(&p, a, n) == 0) return p;
    std::new_handler h = std::get_new_handler();
    if (!h) throw std::bad_alloc();
    h();
  }
}

template <class... A>
void* allocate_nothrow(std::size_t n, A... a) noexcept {
  try {
    return allocate(n, a...);
  } catch (...) {
    return nullptr;
  }
}

}  // namespace

void* operator new(std::size_t n) {
  return allocate(n);
}
void* operator new[](std::size_t n) {
  return allocate(n);
}
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  return allocate_nothrow(n);
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  return allocate_nothrow(n);
}
void* operator new(std::size_t n, std::align_val_t a) {
  return allocate(n, a);
}
void* operator new[](std::size_t n, std::align_val_t a) {
  return allocate(n, a);
}
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return allocate_nothrow(n, a);
}
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return allocate_nothrow(n, a);
}

// The replaced operators pair with the replaced new above (both on malloc/free); GCC 12, inlining
// them into the tests of an ASan unity batch, takes free() for a mismatch
// (-Wmismatched-new-delete).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete(void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete[](void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept {
  std::free(p);
}

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

// ---- tests --------------------------------------------------------------------------------------
namespace {

struct Counts {
  long news = 0, mallocs = 0;
};

// Counts the allocations made between construction and stop() (or destruction).
class CountAllocations {
 public:
  CountAllocations() {
    void* warm[2];
    backtrace(warm, 2);  // the first call loads the unwinder (allocates): do it outside
    n_traces.store(0);
    new_count.store(0);
    malloc_count.store(0);
    counting.store(true);
  }
  ~CountAllocations() { stop(); }
  Counts stop() {
    counting.store(false);
    return {new_count.load(), malloc_count.load()};
  }
};

void print_traces() {
  const int n = n_traces.load();
  for (int k = 0; k < n; ++k) {
    std::fprintf(stderr, "---- allocation %d: call stack\n", k + 1);
    std::fflush(stderr);
    backtrace_symbols_fd(traces[k], trace_depth[k], STDERR_FILENO);
  }
}

// Keeps the compiler from eliding a new/delete pair in the self-test.
void* volatile sink;

TEST(NoAllocation, CounterSeesOperatorNewAndMalloc) {
  Counts c;
  {
    CountAllocations scope;
    sink = new int(1);
    delete static_cast<int*>(sink);
    sink = new (std::align_val_t{64}) double[3];
    ::operator delete[](sink, std::align_val_t{64});
    Eigen::VectorXd v(1000);  // Eigen allocates with std::malloc, not operator new
    sink = v.data();
    c = scope.stop();
  }
  EXPECT_EQ(c.news, 2);
  ASSERT_TRUE(hooks_installed);
  EXPECT_GE(c.mallocs, 2);  // new int (via malloc) and Eigen's malloc
}

// Warm up with a few samples (the first sample has no predictor), then count allocations over
// `count` consecutive samples of the reference run.
void expect_no_allocation(const mo2d::mechanisms::Example& ex) {
  const mo2d::Model model = mo2d::build_model(ex.system);
  mo2d::InverseData data(model, ex.motion, ex.run);
  const int N = ex.run.samples;
  const double t0 = ex.run.t0, t1 = ex.run.t1;
  auto time = [&](int k) { return t0 + (t1 - t0) * k / (N - 1); };
  constexpr int warmup = 5, count = 100;
  ASSERT_GE(N, warmup + count);
  for (int k = 0; k < warmup; ++k) mo2d::inverse_dynamics_sample(model, data, time(k));

  Counts c;
  {
    CountAllocations scope;
    for (int k = warmup; k < warmup + count; ++k)
      mo2d::inverse_dynamics_sample(model, data, time(k));
    c = scope.stop();
  }
  EXPECT_EQ(c.news, 0) << "operator new calls in " << count << " samples";
  EXPECT_EQ(c.mallocs, 0) << "malloc/calloc/realloc calls in " << count << " samples";
  if (c.news != 0 || c.mallocs != 0) print_traces();
  EXPECT_TRUE(std::isfinite(data.u.norm()));
}

// History: at 8fc9055 these failed with 11 malloc calls per sample (0 operator new), all Eigen
// temporaries in inverse_dynamics_sample(): (A * q1 - b).lpNorm() evaluating the product into a
// temporary; lu_K.transpose().solve(...), where Transpose<PartialPivLU> holds a *copy* of the
// decomposition (3 allocations) and the in-place P^T product allocates a bool mask (1); and
// lambda = Y.topRows(m1) * u - z.head(m1). 30c7e75 (in-place LU solves, .noalias() products into
// workspace) removed them. Checked: the default ComplementMethod::prescribed path on the reference
// runs (Newton from the prediction converges; the continuation fallback is not exercised).
// ComplementMethod::recursive and the throwing error paths allocate by design.
TEST(NoAllocation, WhitworthSample) {
  expect_no_allocation(mo2d::mechanisms::whitworth());
}

TEST(NoAllocation, Rrr3Sample) {
  expect_no_allocation(mo2d::mechanisms::rrr3());
}

// Joint friction: the fixed-point iteration of the friction and the reactions per sample reuses
// the workspace (InverseData::friction, friction_next, local_base).
TEST(NoAllocation, SliderCrankWithFrictionSample) {
  mo2d::mechanisms::Example ex = mo2d::mechanisms::slider_crank();
  ex.system.add_friction({.name = "rail_friction", .joint = "rail", .mu = 0.2});
  ex.system.add_friction(
      {.name = "pin_friction", .joint = "crank_pin", .viscous = 0.01, .mu = 0.2, .radius = 0.01});
  expect_no_allocation(ex);
}

// The same run from the scene file: its motions are Expressions evaluated on Jet (recursion over
// the parsed tree, no allocation).
TEST(NoAllocation, Rrr3SceneSample) {
  const mo2d::Scene s = mo2d::load_scene(std::string(MO2D_MECHANISMS_DIR) + "/rrr3.yaml");
  expect_no_allocation({s.system, s.motion, mo2d::inverse_options(s)});
}

// The exact sensitivities of a sample (mo2d/sensitivity.hpp) reuse SensitivityData: the scene's
// slider-crank, its three masses and gravity.
TEST(NoAllocation, SensitivitySample) {
  const std::string path = std::string(MO2D_MECHANISMS_DIR) + "/slider_crank.yaml";
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  const mo2d::Scene s = mo2d::parse_scene(text.str(), path);
  const mo2d::Model m = mo2d::build_scene_model(s);
  const mo2d::InverseOptions o = mo2d::inverse_options(s);
  const std::vector<std::string> names{"m_crank", "m_rod", "m_slider", "gravity"};
  const auto p = mo2d::scene_parameter_models(text.str(), s, {}, {}, names, m, {}, o);
  mo2d::InverseData d(m, s.motion, o);
  mo2d::SensitivityData sd(m, p);
  for (int k = 0; k < 5; ++k) {
    mo2d::inverse_dynamics_sample(m, d, 0.01 * k);
    mo2d::inverse_sensitivity_sample(m, d, p, sd);
  }
  Counts c;
  {
    CountAllocations scope;
    for (int k = 5; k < 105; ++k) {
      mo2d::inverse_dynamics_sample(m, d, 0.005 * k);
      mo2d::inverse_sensitivity_sample(m, d, p, sd);
    }
    c = scope.stop();
  }
  EXPECT_EQ(c.news, 0) << "operator new calls in 100 samples with sensitivities";
  EXPECT_EQ(c.mallocs, 0) << "malloc/calloc/realloc calls in 100 samples with sensitivities";
  if (c.news != 0 || c.mallocs != 0) print_traces();
  EXPECT_GT(sd.efforts.norm(), 0);
}

// One evaluation of forward dynamics on its public workspace (forward_accelerations, the
// integrators' right-hand side) allocates nothing once the workspace is built and a first
// evaluation has sized the factorizations: the double four-bar (M positive definite: the Schur
// solve), the pendulum (M singular: the KKT solve) and the slider-crank with joint friction (the
// reactions' least squares in every evaluation); and the reactions of a recorded sample
// (compute_reactions: the refined least squares, src/forward/least_squares.hpp).
TEST(NoAllocation, ForwardAccelerations) {
  auto expect_none = [](const mo2d::Model& model, const mo2d::State& s, const char* name) {
    mo2d::ForwardData data(model);
    const Eigen::VectorXd u = Eigen::VectorXd::Constant(model.n_inputs(), 0.5);
    mo2d::forward_accelerations(model, data, 0.0, s.q0, s.q1, u);
    data.compute_reactions(0.0, s.q0, s.q1);  // sizes the list of A's entries by body slot
    Counts c;
    {
      CountAllocations scope;
      for (int k = 0; k < 100; ++k) {
        mo2d::forward_accelerations(model, data, 1e-3 * k, s.q0, s.q1, u);
        data.compute_reactions(1e-3 * k, s.q0, s.q1);  // a recorded sample's reactions
      }
      c = scope.stop();
    }
    EXPECT_EQ(c.news, 0) << "operator new calls in 100 evaluations, " << name;
    EXPECT_EQ(c.mallocs, 0) << "malloc/calloc/realloc calls in 100 evaluations, " << name;
    if (c.news != 0 || c.mallocs != 0) print_traces();
    EXPECT_TRUE(data.a.allFinite());
  };
  const mo2d::Model fourbars = mo2d::build_model(mo2d::mechanisms::double_fourbar());
  expect_none(
      fourbars,
      mo2d::consistent_state(fourbars, {.positions = {}, .velocities = {{"crank0.w", -1.0}}}),
      "double four-bar");
  const mo2d::Model pendulum = mo2d::build_model(mo2d::mechanisms::pendulum().system);
  expect_none(pendulum,
              mo2d::consistent_state(pendulum, {.positions = {}, .velocities = {{"link.w", 0.5}}}),
              "pendulum");
  // joint friction: every evaluation iterates the friction with the reactions (least squares)
  const mo2d::Scene fr =
      mo2d::load_scene(std::string(MO2D_MECHANISMS_DIR) + "/slider_crank_friction.yaml");
  const mo2d::Model friction = mo2d::build_scene_model(fr);
  expect_none(friction, mo2d::initial_state(fr, friction), "slider-crank with friction");
}

// The same on the sparse path (sparse_engine.hpp): the Gram matrix's LDL^T of the conditioning
// estimate and the KKT system's KLU refactorization at every evaluation, and, near a singular
// configuration, the augmented-Lagrangian iteration on the sparse Cholesky of H. Eigen's
// SimplicialLLT/LDLT::factorize copy P A P^T into a new matrix at every call, their solve applies
// P^-1 through a temporary mask and vectorD() returns a copy: the engine goes through
// linalg/fixed_cholesky.hpp instead (with vectorD() left in, this test saw 1 malloc per
// evaluation).
TEST(NoAllocation, ForwardAccelerationsSparse) {
  auto expect_none = [](const mo2d::Model& model, const mo2d::State& s, const char* name) {
    mo2d::ForwardOptions o{.integrator = mo2d::Integrator::rk4, .step = 1e-3};
    o.linear_algebra = mo2d::LinearAlgebra::sparse;
    mo2d::ForwardData data(model, o);
    const Eigen::VectorXd u = Eigen::VectorXd::Constant(model.n_inputs(), 0.5);
    mo2d::forward_accelerations(model, data, 0.0, s.q0, s.q1, u);
    Counts c;
    {
      CountAllocations scope;
      for (int k = 0; k < 100; ++k)
        mo2d::forward_accelerations(model, data, 1e-3 * k, s.q0, s.q1, u);
      c = scope.stop();
    }
    EXPECT_EQ(c.news, 0) << "operator new calls in 100 evaluations, " << name;
    EXPECT_EQ(c.mallocs, 0) << "malloc/calloc/realloc calls in 100 evaluations, " << name;
    if (c.news != 0 || c.mallocs != 0) print_traces();
    EXPECT_TRUE(data.a.allFinite());
    EXPECT_GT(data.stats.rhs_evaluations, 100);
  };
  const mo2d::Model fourbars = mo2d::build_model(mo2d::mechanisms::double_fourbar());
  expect_none(
      fourbars,
      mo2d::consistent_state(fourbars, {.positions = {}, .velocities = {{"crank0.w", -1.0}}}),
      "double four-bar");
  const mo2d::Model slider = mo2d::build_model(mo2d::mechanisms::slider_crank().system);
  expect_none(slider,
              mo2d::consistent_state(slider, {.positions = {}, .velocities = {{"crank.w", 2.0}}}),
              "slider-crank");
}

// The contacts' forces (src/contact/contact_forces.hpp) in every evaluation of a contact run: a
// compliant contact while closed (its gap on Jets, the Lankarani-Nikravesh law) and a persistent
// rigid one (its multiplier from the probe workspace's evaluations and a fixed-size LU).
TEST(NoAllocation, ContactForces) {
  mo2d::System sys("contacts");
  sys.add_ground_node("O", {0, 0});
  sys.add_ground_node("S1", {0, 1});
  sys.add_ground_node("S2", {0, -2});
  sys.add_ground_node("L", {-5, -1});
  sys.add_ground_node("R", {5, -1});
  sys.add_body({.name = "rod",
                .nodes = {{"O", {0, 0}}, {"B", {0, -0.8}}},
                .mass = 2,
                .inertia = 0.1,
                .com = mo2d::CenterOfMass::between("O", "B", 0.5)});
  sys.add_revolute({.name = "pivot", .node_a = "ground.O", .node_b = "rod.O"});
  sys.add_body({.name = "ball", .nodes = {{"C", {2, -0.9001}}}, .mass = 1});
  sys.set_gravity({1, -9.81});  // presses the rod's tip on the stop x = 0 from x < 0
  const mo2d::Model model = mo2d::build_model(sys);
  mo2d::ContactLaw soft, hard;
  soft.stiffness = 1e6;
  soft.restitution = 0.8;
  hard.kind = mo2d::ContactLaw::Kind::rigid;
  std::vector<mo2d::detail::CompiledContact> cs = {
      mo2d::detail::compile_contact(model, {.name = "floor",
                                            .point = "ball.C",
                                            .radius = 0.1,
                                            .a = "ground.L",
                                            .b = "ground.R",
                                            .law = soft}),
      mo2d::detail::compile_contact(
          model,
          {.name = "stop", .point = "rod.B", .a = "ground.S2", .b = "ground.S1", .law = hard})};
  mo2d::ForwardOptions o{.integrator = mo2d::Integrator::dopri5};
  mo2d::detail::ContactForces forces(model, std::move(cs), o, 0.0);
  forces.mode = {mo2d::detail::ContactMode::compliant, mo2d::detail::ContactMode::persistent};
  forces.v0 = {0.5, 0};
  o.extra_forces = [&forces](double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1,
                             Eigen::VectorXd& f) { return forces.add(t, q0, q1, f); };
  mo2d::ForwardData data(model, o);
  const mo2d::State s = mo2d::consistent_state(
      model,
      {.positions = {}, .velocities = {{"rod.w", 0.0}, {"ball.C.vx", 0.0}, {"ball.C.vy", -0.3}}});
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(model.n_inputs());
  mo2d::forward_accelerations(model, data, 0.0, s.q0, s.q1, u);
  Counts c;
  {
    CountAllocations scope;
    for (int k = 0; k < 100; ++k) mo2d::forward_accelerations(model, data, 1e-3 * k, s.q0, s.q1, u);
    c = scope.stop();
  }
  EXPECT_EQ(c.news, 0) << "operator new calls in 100 evaluations";
  EXPECT_EQ(c.mallocs, 0) << "malloc/calloc/realloc calls in 100 evaluations";
  if (c.news != 0 || c.mallocs != 0) print_traces();
  // the tip held on the stop (lambda = the pendulum's push, > 0), the ball pushed up
  EXPECT_GT(forces.lambda[1], 0);
  EXPECT_LT(std::abs(data.a[model.rate("ball.C.vy")] + 9.81), 1e3);
  EXPECT_GT(data.a[model.rate("ball.C.vy")], -9.81);
}

// Friction in the contacts' forces (contact_forces.hpp): a compliant contact sliding (its force
// -mu F s), a persistent one sticking (a tangent row), and a block's two corners sticking on the
// ground (equal tangent rows: the null space and the least weighted split, fixed-size).
TEST(NoAllocation, ContactFrictionForces) {
  mo2d::System sys("rough");
  sys.add_ground_node("L", {-5, 0});
  sys.add_ground_node("R", {5, 0});
  sys.add_body({.name = "block",
                .nodes = {{"A", {-0.2, 0}}, {"B", {0.2, 0}}},
                .mass = 2,
                .inertia = 0.05,
                .com = mo2d::CenterOfMass::at_point({0, 0.1})});
  sys.add_body({.name = "ball", .nodes = {{"C", {2, 0.0999}}}, .mass = 1, .inertia = 0.01});
  sys.set_gravity({3, -9.81});  // pushes the block along: its corners' friction holds it
  const mo2d::Model model = mo2d::build_model(sys);
  mo2d::ContactLaw soft, hard;
  soft.stiffness = 1e6;
  soft.restitution = 0.8;
  soft.friction = 0.3;
  hard.kind = mo2d::ContactLaw::Kind::rigid;
  hard.friction = 0.5;
  std::vector<mo2d::detail::CompiledContact> cs;
  cs.push_back(mo2d::detail::compile_contact(model, {.name = "floor",
                                                     .point = "ball.C",
                                                     .radius = 0.1,
                                                     .a = "ground.L",
                                                     .b = "ground.R",
                                                     .law = soft}));
  for (const char* corner : {"block.A", "block.B"})
    cs.push_back(mo2d::detail::compile_contact(
        model, {.name = corner, .point = corner, .a = "ground.L", .b = "ground.R", .law = hard}));
  mo2d::ForwardOptions o{.integrator = mo2d::Integrator::dopri5};
  mo2d::detail::ContactForces forces(model, std::move(cs), o, 0.0);
  using mo2d::detail::ContactMode;
  using mo2d::detail::SlideMode;
  forces.mode = {ContactMode::compliant, ContactMode::persistent, ContactMode::persistent};
  forces.slide = {SlideMode::slip, SlideMode::stick, SlideMode::stick};
  forces.v0 = {0.5, 0, 0};
  o.extra_forces = [&forces](double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1,
                             Eigen::VectorXd& f) { return forces.add(t, q0, q1, f); };
  mo2d::ForwardData data(model, o);
  const mo2d::State s = mo2d::consistent_state(model, {.positions = {},
                                                       .velocities = {{"block.A.vx", 0.0},
                                                                      {"block.A.vy", 0.0},
                                                                      {"block.w", 0.0},
                                                                      {"ball.C.vx", 1.0},
                                                                      {"ball.C.vy", -0.3},
                                                                      {"ball.w", 0.0}}});
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(model.n_inputs());
  mo2d::forward_accelerations(model, data, 0.0, s.q0, s.q1, u);
  Counts c;
  {
    CountAllocations scope;
    for (int k = 0; k < 100; ++k) mo2d::forward_accelerations(model, data, 1e-3 * k, s.q0, s.q1, u);
    c = scope.stop();
  }
  EXPECT_EQ(c.news, 0) << "operator new calls in 100 evaluations";
  EXPECT_EQ(c.mallocs, 0) << "malloc/calloc/realloc calls in 100 evaluations";
  if (c.news != 0 || c.mallocs != 0) print_traces();
  // the corners hold the block against the push 3 m: friction -6 N in all, shared in proportion
  // to the normal forces (which sum to m g)
  EXPECT_NEAR(forces.tangential[1] + forces.tangential[2], -6, 1e-9);
  EXPECT_NEAR(forces.normal[1] + forces.normal[2], 2 * 9.81, 1e-9);
  EXPECT_NEAR(forces.tangential[1] / forces.normal[1], forces.tangential[2] / forces.normal[2],
              1e-9);
  EXPECT_NEAR(forces.tangential[0], -0.3 * forces.normal[0], 1e-12);  // the ball slides forward
}

// A pin held on a slot's wall (src/contact/slot.hpp): the slot's three parts' gaps, the wall's
// multiplier and the slot's region condition, per evaluation without allocation.
TEST(NoAllocation, SlotContact) {
  mo2d::System sys("slot_alloc");
  sys.add_ground_node("A", {0, 0});
  sys.add_ground_node("B", {1, 0});
  sys.add_body({.name = "ball", .nodes = {{"C", {0.5, 0.05}}}, .mass = 1});
  sys.set_gravity({0, 9.81});  // presses the pin on the left wall (l = h = 0.05)
  const mo2d::Model model = mo2d::build_model(sys);
  mo2d::ContactLaw hard;
  hard.kind = mo2d::ContactLaw::Kind::rigid;
  std::vector<mo2d::detail::CompiledContact> cs;
  mo2d::detail::compile_contacts(model,
                                 {.name = "slot",
                                  .point = "ball.C",
                                  .radius = 0.1,
                                  .target = mo2d::ContactDef::Target::slot,
                                  .a = "ground.A",
                                  .b = "ground.B",
                                  .width = 0.3,
                                  .law = hard},
                                 cs);
  mo2d::ForwardOptions o{.integrator = mo2d::Integrator::dopri5};
  mo2d::detail::ContactForces forces(model, std::move(cs), o, 0.0);
  mo2d::detail::SlotRegions regions(forces.contacts);
  const mo2d::State s = mo2d::consistent_state(
      model, {.positions = {}, .velocities = {{"ball.C.vx", 0.3}, {"ball.C.vy", 0.0}}});
  regions.start(model, s.q0);
  forces.mode[0] = mo2d::detail::ContactMode::persistent;
  o.extra_forces = [&forces](double t, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1,
                             Eigen::VectorXd& f) { return forces.add(t, q0, q1, f); };
  mo2d::ForwardData data(model, o);
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(model.n_inputs());
  mo2d::forward_accelerations(model, data, 0.0, s.q0, s.q1, u);
  double c = 0;
  Counts n;
  {
    CountAllocations scope;
    for (int k = 0; k < 100; ++k) {
      mo2d::forward_accelerations(model, data, 1e-3 * k, s.q0, s.q1, u);
      for (int i = 0; i < 3; ++i) (void)forces.gap(i, s.q0, s.q1);
      c += regions.condition(model, s.q0);
    }
    n = scope.stop();
  }
  EXPECT_EQ(n.news, 0) << "operator new calls in 100 evaluations";
  EXPECT_EQ(n.mallocs, 0) << "malloc/calloc/realloc calls in 100 evaluations";
  if (n.news != 0 || n.mallocs != 0) print_traces();
  EXPECT_NEAR(forces.lambda[0], 9.81, 1e-9);  // the wall holds the pin's weight
  EXPECT_NEAR(c, 100 * 0.1, 1e-9);            // inside: min(L - s, w/2 - |l|, s) = 0.1
}

// A cam profile's gap (src/contact/profile.hpp): its closest point's Newton from the previous one,
// the gap on Jets and its gradient, and the gap alone (what the events watch), at moving states.
TEST(NoAllocation, ProfileGap) {
  mo2d::System sys("cam");
  sys.add_ground_node("G", {0, 0});
  sys.add_body({.name = "cam",
                .nodes = {{"O", {0, 0}}, {"A", {0.03, 0}}},
                .mass = 1,
                .inertia = 1e-3,
                .com = mo2d::CenterOfMass::between("O", "A", 0)});
  sys.add_body({.name = "ball", .nodes = {{"C", {0.01, 0.06}}}, .mass = 1, .inertia = 1e-4});
  const mo2d::Model model = mo2d::build_model(sys);
  std::vector<double> x, y;
  for (int i = 0; i <= 72; ++i) {
    x.push_back(2 * std::numbers::pi * i / 72);
    y.push_back(0.05 + 0.01 * std::cos(3 * x.back()));
  }
  mo2d::ContactLaw hard;
  hard.kind = mo2d::ContactLaw::Kind::rigid;
  const mo2d::detail::CompiledContact cc = mo2d::detail::compile_contact(
      model, {.name = "cam",
              .point = "ball.C",
              .radius = 0.01,
              .target = mo2d::ContactDef::Target::profile,
              .a = "cam.O",
              .b = "cam.A",
              .profile = std::make_shared<const mo2d::LookupTable>(
                  "r", x, y,
                  mo2d::TableOptions{mo2d::Interpolation::cubic, mo2d::Extrapolation::periodic}),
              .law = hard});
  mo2d::GapValue g;
  g.J = Eigen::VectorXd::Zero(model.n1);
  Eigen::VectorXd q0 = model.q0, q1 = Eigen::VectorXd::Ones(model.n1);
  const int c = model.bodies[1].nodes[0].var;
  mo2d::detail::gap_into(model, cc, q0, q1, g);
  double sum = 0;
  Counts n;
  {
    CountAllocations scope;
    for (int k = 0; k < 100; ++k) {
      q0[c] = 0.01 + 1e-3 * k;  // the ball moves around the cam: the closest point follows
      mo2d::detail::gap_into(model, cc, q0, q1, g);
      sum += g.g + mo2d::detail::gap_only(model, cc, q0);
    }
    n = scope.stop();
  }
  EXPECT_EQ(n.news, 0) << "operator new calls in 100 evaluations";
  EXPECT_EQ(n.mallocs, 0) << "malloc/calloc/realloc calls in 100 evaluations";
  if (n.news != 0 || n.mallocs != 0) print_traces();
  EXPECT_TRUE(std::isfinite(sum));
}

}  // namespace
