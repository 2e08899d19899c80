#include "models/knit/knit_rest_shape.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "models/knit/knit_model.h"

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

KnitRestShape relax_knit_tile(const Scene& scene) {
  std::unique_ptr<KnitModel> tile = KnitModel::tile(scene);
  KnitModel& m = *tile;
  const int n = m.num_dofs();
  std::vector<char> held(n, 0);
  for (int d : m.gauge_dofs()) held[d] = 1;
  std::vector<int> free;
  for (int d = 0; d < n; ++d)
    if (!held[d]) free.push_back(d);
  const int nf = static_cast<int>(free.size());
  std::vector<int> position(n, -1);
  for (int k = 0; k < nf; ++k) position[free[k]] = k;

  double ks = 0.0;
  for (const auto& [name, y] : scene.yarn_types)
    ks = std::max(ks, y.stretch_modulus_Pa * std::numbers::pi * scene.radius_m * scene.radius_m);
  const double tol = kKnitRestTolerance * ks;

  Vec q = m.initial_q(), v = Vec::Zero(n);
  Evaluation eval;
  allocate_evaluation(m, eval);
  KnitRestShape out;
  out.energy_generated_J = m.potential_energy(q);
  double energy = out.energy_generated_J, mu = 0.0;
  auto residual = [&](const Vec& f) {
    double r = 0.0;
    for (int d : free) r = std::max(r, std::abs(f[d]));
    return r;
  };
  Eigen::SimplicialLDLT<SparseMatrix> solver;
  for (out.iterations = 0; out.iterations < 400; ++out.iterations) {
    m.evaluate(0.0, q, v, kForce | kDfdq, eval);
    out.residual_N = residual(eval.force);
    if (out.residual_N <= tol) break;
    // A = −K_ff + μ·max diag, the static Newton step A dq = f_f, shifted until the energy descends.
    std::vector<Eigen::Triplet<double>> entries;
    double diag = 0.0;
    for (int c = 0; c < eval.dfdq.outerSize(); ++c)
      for (SparseMatrix::InnerIterator it(eval.dfdq, c); it; ++it) {
        const int i = position[it.row()], j = position[it.col()];
        if (i < 0 || j < 0) continue;
        entries.emplace_back(i, j, -it.value());
        if (i == j) diag = std::max(diag, -it.value());
      }
    SparseMatrix A(nf, nf);
    A.setFromTriplets(entries.begin(), entries.end());
    Vec rhs(nf);
    for (int k = 0; k < nf; ++k) rhs[k] = eval.force[free[k]];
    bool stepped = false;
    for (int attempt = 0; attempt < 40 && !stepped; ++attempt) {
      SparseMatrix shifted = A;
      for (int k = 0; k < nf; ++k) shifted.coeffRef(k, k) += mu * std::max(diag, 1e-300);
      solver.compute(shifted);
      if (solver.info() == Eigen::Success) {
        const Vec dq = solver.solve(rhs);
        Vec trial = q;
        for (int k = 0; k < nf; ++k) trial[free[k]] += dq[k];
        const double e = trial.allFinite() && m.invalid_state(trial).empty() ? m.potential_energy(trial) : INFINITY;
        if (e <= energy) {
          q = trial;
          energy = e;
          stepped = true;
          mu = mu > 1e-12 ? mu / 4.0 : 0.0;
          break;
        }
      }
      mu = mu > 0.0 ? mu * 8.0 : 1e-8;
    }
    if (!stepped) break;
  }
  if (!(out.residual_N <= tol)) {
    std::ostringstream why;
    why << "the rest shape of the knit tile did not converge: residual " << out.residual_N << " N > " << tol
        << " N after " << out.iterations << " Newton steps";
    throw std::runtime_error(why.str());
  }
  out.energy_relaxed_J = energy;
  out.courses = m.graph().layout().courses;
  out.wales = m.graph().layout().wales;
  for (const KnitNode& node : m.graph().nodes()) {
    out.dx.push_back(q.segment<3>(node.x_dof) - node.x);
    std::vector<double> du;
    for (size_t s = 0; s < node.coord.size(); ++s) du.push_back(m.coordinate(q, node.coord[s]) - node.u[s]);
    out.du.push_back(du);
  }
  return out;
}

const KnitRestShape& relaxed_tile(const Scene& scene) {
  static std::mutex lock;
  static std::map<std::string, KnitRestShape> cache;
  const std::string key = cache_key(scene);
  std::lock_guard<std::mutex> guard(lock);
  auto it = cache.find(key);
  if (it == cache.end()) it = cache.emplace(key, relax_knit_tile(scene)).first;
  return it->second;
}

}  // namespace wl
