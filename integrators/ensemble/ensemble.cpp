// The ensemble stepper's dispatch (ensemble.hpp): which instruction sets this
// CPU has, which models the kernels apply to, and the lane block. Which
// scheme has which kernel is its registry entry's (SchemeInfo::lanes).
// Compiled for the baseline instruction set; it includes no xsimd header.
#include "integrators/ensemble/ensemble.hpp"

#include <atomic>
#include <cmath>
#include <type_traits>
#include <variant>

#include "integrators/schemes/cayley_quaternion.hpp"
#include "integrators/ensemble/cardan_tangent_ensemble.hpp"
#include "integrators/ensemble/tangent_ensemble.hpp"
#include "integrators/schemes/moser_veselov_diagonal.hpp"
#include "integrators/registry/registry.hpp"

namespace lgi::integrators::ensemble {

namespace {

bool cpu_has(Isa isa) {
#if defined(LGI_ENSEMBLE_X86)
  switch (isa) {
    case Isa::baseline: return true;
    case Isa::avx2: return __builtin_cpu_supports("avx2");
    case Isa::avx512: return __builtin_cpu_supports("avx512f");  // libgcc also checks the OS saves the state
  }
  return false;
#else
  return isa == Isa::baseline;
#endif
}

KernelSet kernels(Isa isa) {
#if defined(LGI_ENSEMBLE_X86)
  if (isa == Isa::avx2) return avx2_kernels();
  if (isa == Isa::avx512) return avx512_kernels();
#endif
  return baseline_kernels();
}

/// A kind of lane kernel's entry in a KernelSet and its cost per step.
struct KindKernel {
  StepKernel KernelSet::*kernel = nullptr;
  int rhs_per_step = 0;
};
KindKernel kernel_of(LaneKernel kind) {
  switch (kind) {
    case LaneKernel::rkmk4: return {&KernelSet::rkmk4, 4};
    case LaneKernel::dmv_diagonal: return {&KernelSet::dmv_pre, 1};
    case LaneKernel::none: break;
  }
  return {};
}

static_assert(12 + moser_veselov::CayleyPredictor::memory_size == static_cast<std::size_t>(dmv_rows::memory),
              "dmv_rows must follow StepMemory::save (dmv_fallback.hpp copies one into the other)");

void copy3(const lie::Vec3& v, double (&out)[3]) {
  for (int i = 0; i < 3; ++i) out[i] = v(i);
}

// The kernels mirror the scene model's terms in this order (ensemble_model.hpp).
static_assert(std::is_same_v<system::SceneModel,
                             system::RigidBody<system::Declared<system::GravityTerm>, system::Declared<system::SpringTerm>,
                                               system::Declared<system::HarmonicDriveTerm>,
                                               system::Declared<system::MagneticDipoleTerm>>>,
              "the scene terms changed: update EnsembleModel, scene_torque() and describe() to match");

/// The kernels' view of a model; nullopt with the reason where no kernel applies.
std::optional<EnsembleModel> describe(const system::AnyModel& any, std::string* why) {
  EnsembleModel m;
  const system::Inertia& inertia = std::visit([](const auto& model) -> const system::Inertia& { return model.inertia; }, any);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m.J_inv[i][j] = inertia.J_inv(i, j);
  const auto* scene = std::get_if<system::SceneModel>(&any);
  if (!scene) return m;  // the free body
  m.free_body = false;
  const auto& [gravity, spring, drive, magnetic] = scene->terms;
  if (spring.active) {
    if (why) *why = "no ensemble kernel for a spring (a matrix logarithm per lane)";
    return std::nullopt;
  }
  m.gravity = gravity.active;
  copy3(gravity.term.mg_chi, m.mg_chi);
  m.drive = drive.active;
  copy3(drive.term.amplitude, m.drive_amplitude);
  m.drive_frequency = drive.term.angular_frequency;
  m.drive_phase = drive.term.phase;
  m.magnetic = magnetic.active;
  copy3(magnetic.term.field, m.magnetic_field);
  copy3(magnetic.term.minus_moment, m.magnetic_minus_moment);
  return m;
}

std::atomic<int> sweep_choice{-2};  // −2: not set (best_isa()), −1: none, else an Isa

}  // namespace

const char* isa_name(Isa isa) {
  switch (isa) {
    case Isa::baseline: return kernels(Isa::baseline).isa;
    case Isa::avx2: return "avx2";
    case Isa::avx512: return "avx512";
  }
  return "";
}

std::optional<Isa> parse_isa(std::string_view name) {
  for (Isa isa : {Isa::baseline, Isa::avx2, Isa::avx512})
    if (name == isa_name(isa)) return isa;
  return std::nullopt;
}

bool isa_available(Isa isa) { return cpu_has(isa); }

std::vector<Isa> available_isas() {
  std::vector<Isa> out;
  for (Isa isa : {Isa::baseline, Isa::avx2, Isa::avx512})
    if (isa_available(isa)) out.push_back(isa);
  return out;
}

Isa best_isa() { return available_isas().back(); }

int isa_lanes(Isa isa) { return kernels(isa).lanes; }

std::optional<Isa> sweep_isa() {
  const int c = sweep_choice.load();
  if (c == -2) return best_isa();
  if (c == -1) return std::nullopt;
  return static_cast<Isa>(c);
}

void set_sweep_isa(std::optional<Isa> isa) { sweep_choice = isa ? static_cast<int>(*isa) : -1; }

std::optional<EnsembleModel> ensemble_model(const system::AnyModel& model, std::string* why) {
  return describe(model, why);
}

TangentKernelSet tangent_kernels(Isa isa) {
#if defined(LGI_ENSEMBLE_X86)
  if (isa == Isa::avx2) return avx2_tangent_kernels();
  if (isa == Isa::avx512) return avx512_tangent_kernels();
#endif
  (void)isa;
  return baseline_tangent_kernels();
}

CardanTangentKernelSet cardan_tangent_kernels(Isa isa) {
#if defined(LGI_ENSEMBLE_X86)
  if (isa == Isa::avx2) return avx2_cardan_tangent_kernels();
  if (isa == Isa::avx512) return avx512_cardan_tangent_kernels();
#endif
  (void)isa;
  return baseline_cardan_tangent_kernels();
}

bool has_kernel(const SchemeInfo& scheme) { return scheme.lanes.kernel != LaneKernel::none; }

bool has_kernel(std::string_view scheme) {
  const SchemeInfo* s = find_scheme(scheme);
  return s && has_kernel(*s);
}

/// Why the DMV kernel does not apply to this model, or empty.
std::string dmv_unsupported(std::string_view scheme, const system::AnyModel& model) {
  const auto* free = std::get_if<system::FreeBody>(&model);
  if (!free) return "no ensemble kernel for " + std::string(scheme) + " with torques (only on a free body)";
  const lie::Mat3& J = free->inertia.J;
  if (!(J(0, 1) == 0.0 && J(0, 2) == 0.0 && J(1, 0) == 0.0 && J(1, 2) == 0.0 && J(2, 0) == 0.0 && J(2, 1) == 0.0))
    return "no ensemble kernel for " + std::string(scheme) + " with a non-diagonal inertia tensor";
  return {};
}

std::string unsupported_reason(const SchemeInfo& scheme, const system::AnyModel& model) {
  if (std::string why = integrators::unsupported_reason(scheme, model); !why.empty()) return why;
  if (!has_kernel(scheme)) return "no ensemble kernel for " + scheme.name;
  if (scheme.lanes.kernel == LaneKernel::dmv_diagonal) return dmv_unsupported(scheme.name, model);
  std::string why;
  if (!describe(model, &why)) return why;
  return {};
}

std::string unsupported_reason(std::string_view scheme, const system::AnyModel& model) {
  const SchemeInfo* s = find_scheme(scheme);
  if (!s) return "unknown scheme '" + std::string(scheme) + "' (lgi schemes lists them)";
  return ensemble::unsupported_reason(*s, model);
}

std::optional<EnsembleStepper> EnsembleStepper::make(const SchemeInfo& scheme, const system::AnyModel& model,
                                                     Isa isa) {
  if (!isa_available(isa) || !ensemble::unsupported_reason(scheme, model).empty()) return std::nullopt;
  std::optional<EnsembleModel> m = describe(model, nullptr);
  const KindKernel k = kernel_of(scheme.lanes.kernel);
  if (!m || !k.kernel || !scheme.lanes.run) return std::nullopt;
  const bool with_fallback = scheme.lanes.fallback != nullptr;
  if (with_fallback && !std::holds_alternative<system::FreeBody>(model)) return std::nullopt;
  const KernelSet set = kernels(isa);
  EnsembleStepper e;
  if (with_fallback) e.fallback_ = scheme.lanes.fallback(std::get<system::FreeBody>(model), *m);
  e.model_ = *m;
  e.kernel_ = set.*(k.kernel);
  e.run_lanes_ = scheme.lanes.run;
  e.scheme_ = scheme.name;
  e.lanes_ = set.lanes;
  e.rhs_per_step_ = k.rhs_per_step;
  e.isa_ = isa;
  return e;
}

std::optional<EnsembleStepper> EnsembleStepper::make(std::string_view scheme, const system::AnyModel& model, Isa isa) {
  const SchemeInfo* s = find_scheme(scheme);
  if (!s) return std::nullopt;
  return make(*s, model, isa);
}

void EnsembleStepper::set_lane(int lane, const State& s) {
  const auto l = static_cast<std::size_t>(lane);
  set_active(lane, true);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) block_.row[3 * i + j][l] = s.R(i, j);
    block_.row[9 + i][l] = s.Pi(i);
  }
}

void EnsembleStepper::get_lane(int lane, State& s) const {
  const auto l = static_cast<std::size_t>(lane);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) s.R(i, j) = block_.row[3 * i + j][l];
    s.Pi(i) = block_.row[9 + i][l];
  }
  if (fallback_ && model_.preprocessed) {  // the attitude is q (dmv_rows::quaternion), R(q) as the scalar scheme writes it
    moser_veselov::CayleyQuaternion kept;
    for (int i = 0; i < 4; ++i) kept.q[i] = memory_.row[dmv_rows::quaternion + i][l];
    kept.write(s.R);
  }
}

StepStatus EnsembleStepper::start_lane(int lane, const State& s, double t0) {
  set_lane(lane, s);
  return fallback_ ? fallback_->start(lane, s, t0, memory_) : StepStatus{};
}

bool EnsembleStepper::step(double t, double h, int retry_halving) {
  if (kernel_(model_, block_, memory_, t, h)) {  // every active lane stepped by the kernel, and finite
    for (int l = 0; l < max_lanes; ++l) kernel_stepped_[l] = finite_[l] = true;
    if (fallback_) kernel_lane_steps_ += active_count();
    return true;
  }
  if (fallback_) {
    for (int l = 0; l < lanes_; ++l) {
      kernel_stepped_[l] = memory_.row[dmv_rows::stepped][l] == 1.0;
      if (!active_[l]) continue;
      if (kernel_stepped_[l]) ++kernel_lane_steps_;
      else fallback_->step(l, block_, memory_, t, h, retry_halving, outcome_[l]);
    }
  }
  // As detail::finite_state: x − x is 0 for a finite x and NaN otherwise.
  double z[max_lanes] = {};
  for (const auto& row : block_.row)
    for (int l = 0; l < max_lanes; ++l) z[l] += row[l] - row[l];
  for (int l = 0; l < max_lanes; ++l) finite_[l] = z[l] == 0.0;
  return false;
}

int EnsembleStepper::active_count() const {
  int n = 0;
  for (int l = 0; l < lanes_; ++l) n += active_[l] ? 1 : 0;
  return n;
}

void EnsembleStepper::set_active(int lane, bool active) {
  active_[lane] = active;
  memory_.row[dmv_rows::active][lane] = active ? 1.0 : 0.0;
}

const LaneOutcome& EnsembleStepper::outcome(int lane) const {
  // A lane the kernel stepped: one Newton correction, one evaluation (strang_step).
  static constexpr LaneOutcome kernel_step{.status = {.converged = true, .iterations = 1},
                                           .work = {.rhs_evaluations = 1, .newton_iterations_max = 1}};
  return kernel_stepped_[lane] ? kernel_step : outcome_[lane];
}

void EnsembleStepper::save_lane_memory(int lane, std::span<double> out) const {
  for (std::size_t r = 0; r < out.size() && r < static_cast<std::size_t>(dmv_rows::memory); ++r)
    out[r] = memory_.row[r][lane];
}

bool EnsembleStepper::step_lane_from(int lane, std::span<const double> snapshot, State& x, double t, double h,
                                     int retry_halving, WorkCounters& work) {
  return fallback_ && fallback_->step_from(lane, snapshot, x, t, h, retry_halving, work);
}

}  // namespace lgi::integrators::ensemble
