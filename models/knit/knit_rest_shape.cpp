#include "models/knit/knit_rest_shape.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "models/core/energy_descent.h"
#include "models/knit/knit_model.h"
#include "models/knit/knit_scene_error.h"

namespace wl {
namespace {

std::string cache_key(const Scene& s) {
  std::ostringstream k;
  k.precision(17);
  const KnitPattern& p = *s.knit;
  k << static_cast<int>(p.kind) << ' ' << s.spacing_m << ' ' << p.course_spacing_m << ' ' << s.radius_m << ' '
    << p.roll_stiffness_N << ' ' << p.stitch_length_stiffness_N << ' ' << p.compression_stiffness_N_per_m << ' '
    << s.sliding << ' ' << s.terms.stretch << ' ' << s.terms.bending;
  for (const std::string& name : s.warp_yarn_types) {
    const YarnType& y = s.yarn_types.at(name);
    k << ' ' << y.stretch_modulus_Pa << ' ' << y.bending_modulus_Pa;
  }
  return k.str();
}

}  // namespace

double stiffest_yarn_N(const Scene& scene) {
  double ks = 0.0;
  for (const auto& [name, y] : scene.yarn_types)
    ks = std::max(ks, y.stretch_modulus_Pa * std::numbers::pi * scene.radius_m * scene.radius_m);
  return ks;
}

namespace {

// The generated period lengths (wales·W, courses·C).
std::array<double, 2> generated_period(const Scene& scene) {
  const KnitLayout L = knit_layout(scene, true);
  return {L.wales * L.wale_spacing, L.courses * L.course_spacing};
}

// Node positions of a tile state moved from period scale `from` to `to`
// affinely (a warm start; coordinates unchanged).
void rescale_positions(const KnitModel& m, Vec& q, const std::array<double, 2>& from, const std::array<double, 2>& to) {
  for (const KnitNode& n : m.graph().nodes())
    for (int c = 0; c < 2; ++c) q[n.x_dof + c] *= to[c] / from[c];
}

// Relaxes the tile at period scale s from q (in place) into `out`.
void relax_at(const Scene& scene, const std::array<double, 2>& s, Vec& q, KnitRestShape& out) {
  std::unique_ptr<KnitModel> tile = KnitModel::tile(scene, s);
  const double tol = kKnitRestTolerance * stiffest_yarn_N(scene);
  const DescentResult d = descend_energy(*tile, q, tile->gauge_dofs(), tol);
  out.residual_N = d.residual_N;
  out.energy_relaxed_J = d.energy_J;
  out.iterations += d.steps;
  if (!(out.residual_N <= tol)) {
    std::ostringstream why;
    why << "the rest shape of the knit tile did not converge at period scale (" << s[0] << ", " << s[1]
        << "): residual " << out.residual_N << " N > " << tol << " N after " << out.iterations << " Newton steps";
    throw std::runtime_error(why.str());
  }
  out.period_scale = s;
  out.courses = tile->graph().layout().courses;
  out.wales = tile->graph().layout().wales;
  out.dx.clear();
  out.du.clear();
  for (const KnitNode& node : tile->graph().nodes()) {
    out.dx.push_back(q.segment<3>(node.x_dof) - node.x);
    std::vector<double> du;
    for (size_t k = 0; k < node.coord.size(); ++k) du.push_back(tile->coordinate(q, node.coord[k]) - node.u[k]);
    out.du.push_back(du);
  }
}

// The generated tile state at period scale s (positions moved affinely).
Vec generated_state(const Scene& scene, const std::array<double, 2>& s, KnitRestShape& out) {
  std::unique_ptr<KnitModel> tile = KnitModel::tile(scene);
  Vec q = tile->initial_q();
  out.energy_generated_J = tile->potential_energy(q);
  rescale_positions(*tile, q, {1.0, 1.0}, s);
  return q;
}

}  // namespace

std::array<double, 2> knit_period_force(const Scene& scene, const std::array<double, 2>& s, const Vec& q) {
  const std::array<double, 2> length = generated_period(scene);
  constexpr double h = 1e-6;  // relative step in the period scale
  std::array<double, 2> force{};
  for (int i = 0; i < 2; ++i) {
    std::array<double, 2> plus = s, minus = s;
    plus[i] += h;
    minus[i] -= h;
    const double e_plus = KnitModel::tile(scene, plus)->potential_energy(q);
    const double e_minus = KnitModel::tile(scene, minus)->potential_energy(q);
    force[i] = (e_plus - e_minus) / (2.0 * h * length[i]);
  }
  return force;
}

KnitRestShape relax_knit_tile(const Scene& scene, const std::array<double, 2>& s) {
  KnitRestShape out;
  Vec q = generated_state(scene, s, out);
  relax_at(scene, s, q, out);
  out.period_force_N = knit_period_force(scene, s, q);
  return out;
}

KnitRestShape relax_knit_tile(const Scene& scene) { return relax_knit_tile(scene, {1.0, 1.0}); }

// Newton's method on P(ℓ) = 0, its 2×2 Jacobian by differences of P between
// relaxed tiles, each step shortened until the relaxed energy descends
// (docs/models.md §11.3.1).
KnitPeriodRelaxation relax_knit_period(const Scene& scene, int max_steps) {
  KnitPeriodRelaxation result;
  KnitRestShape& out = result.rest;
  std::array<double, 2> s{1.0, 1.0};
  Vec q = generated_state(scene, s, out);
  relax_at(scene, s, q, out);
  out.period_force_N = knit_period_force(scene, s, q);
  result.fixed_period_energy_J = out.energy_relaxed_J;
  const std::array<double, 2> length = generated_period(scene);
  const double tol = kKnitPeriodTolerance * stiffest_yarn_N(scene);
  const std::unique_ptr<KnitModel> shape = KnitModel::tile(scene);  // node numbering for rescale_positions
  auto largest = [](const std::array<double, 2>& p) { return std::max(std::abs(p[0]), std::abs(p[1])); };
  for (; out.period_iterations < max_steps; ++out.period_iterations) {
    const std::array<double, 2> P = out.period_force_N;
    if (largest(P) <= tol) {
      result.converged = true;
      return result;
    }
    Eigen::Matrix2d J;  // ∂P_i/∂ℓ_j
    constexpr double delta = 1e-4;
    for (int j = 0; j < 2; ++j) {
      std::array<double, 2> sj = s;
      sj[j] += delta;
      Vec qj = q;
      rescale_positions(*shape, qj, s, sj);
      KnitRestShape probe;
      relax_at(scene, sj, qj, probe);
      const std::array<double, 2> Pj = knit_period_force(scene, sj, qj);
      for (int i = 0; i < 2; ++i) J(i, j) = (Pj[i] - P[i]) / (delta * length[j]);
      out.iterations += probe.iterations;
    }
    const Eigen::Vector2d p(P[0], P[1]);
    Eigen::Vector2d dl = -J.fullPivLu().solve(p);
    if (!dl.allFinite() || dl.dot(p) >= 0.0) dl = -p / std::max(J.diagonal().cwiseAbs().maxCoeff(), 1e-300);
    Eigen::Vector2d ds(dl[0] / length[0], dl[1] / length[1]);
    if (ds.cwiseAbs().maxCoeff() > 0.1) ds *= 0.1 / ds.cwiseAbs().maxCoeff();
    bool accepted = false;
    for (int halving = 0; halving < 20 && !accepted; ++halving, ds *= 0.5) {
      const std::array<double, 2> trial_s{s[0] + ds[0], s[1] + ds[1]};
      Vec trial_q = q;
      rescale_positions(*shape, trial_q, s, trial_s);
      KnitRestShape trial;
      trial.iterations = out.iterations;
      trial.energy_generated_J = out.energy_generated_J;
      trial.period_iterations = out.period_iterations;
      try {
        relax_at(scene, trial_s, trial_q, trial);
      } catch (const std::runtime_error&) {
        continue;
      }
      if (trial.energy_relaxed_J > out.energy_relaxed_J) continue;
      trial.period_force_N = knit_period_force(scene, trial_s, trial_q);
      out = trial;
      q = trial_q;
      s = trial_s;
      accepted = true;
    }
    if (!accepted) break;
  }
  std::ostringstream why;
  why << "the period of the knit tile did not relax: net period force (" << out.period_force_N[0] << ", "
      << out.period_force_N[1] << ") N, bound " << tol << " N, at period scale (" << s[0] << ", " << s[1] << ") after "
      << out.period_iterations << " steps";
  result.message = why.str();
  return result;
}

Vec knit_tile_state(const Scene& scene, const KnitRestShape& rest) {
  const std::unique_ptr<KnitModel> tile = KnitModel::tile(scene, rest.period_scale);
  Vec q = tile->initial_q();
  for (int k = 0; k < tile->graph().num_nodes(); ++k) {
    const KnitNode& node = tile->graph().node(k);
    q.segment<3>(node.x_dof) = node.x + rest.dx[k];
    for (size_t s = 0; s < node.coord.size(); ++s)
      if (is_dof(node.coord[s])) q[node.coord[s]] = node.u[s] + rest.du[k][s];
  }
  return q;
}

namespace {

// A tile that does not relax is a scene the knit model cannot take (its keys
// are each in range, together they are not): a located SceneError.
KnitRestShape relaxed_or_refused(const Scene& scene) {
  try {
    return relax_knit_tile(scene);
  } catch (const SceneError&) {
    throw;
  } catch (const std::runtime_error& e) {
    refuse_knit_scene(scene, "a knit whose periodic rest tile relaxes to static equilibrium (docs/models.md §11.3)",
                      e.what());
  }
}

KnitRestShape rest_shape_of(const Scene& scene) {
  if (!(scene.knit->compression_stiffness_N_per_m > 0.0)) {
    KnitRestShape fixed = relaxed_or_refused(scene);
    fixed.period_note = "generated period: without contact compression the tile has no rest period";
    return fixed;
  }
  KnitPeriodRelaxation relaxed;
  try {
    relaxed = relax_knit_period(scene);
  } catch (const SceneError&) {
    throw;
  } catch (const std::runtime_error& e) {  // the tile at the generated period decides below
    relaxed.message = std::string("the period did not relax: ") + e.what();
  }
  if (relaxed.converged) {
    relaxed.rest.period_relaxed = true;
    return relaxed.rest;
  }
  KnitRestShape fixed = relaxed_or_refused(scene);
  fixed.period_note = relaxed.message + "; the generated period is kept";
  return fixed;
}

}  // namespace

const KnitRestShape& relaxed_tile(const Scene& scene) {
  static std::mutex lock;
  static std::map<std::string, KnitRestShape> cache;
  const std::string key = cache_key(scene);
  std::lock_guard<std::mutex> guard(lock);
  auto it = cache.find(key);
  if (it == cache.end()) it = cache.emplace(key, rest_shape_of(scene)).first;
  return it->second;
}

}  // namespace wl
