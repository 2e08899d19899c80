// Exact derivatives of the contact normal force, docs/models.md §3.6.1.
//
// F_n = ReLU(g), g = ½ nᵀ(F^u − F^v), is differentiated in reverse order: the
// adjoint a = ½n of F^u (−a of F^v) goes back through each stretch and bending
// element that puts force on the node (their local Jacobians) to the crimped
// positions x_k ∓ R n_k and the sliding coordinates; the crimp passes it on to
// x_k and to n_k, and n_k (with ½(F^u − F^v) for the node's own normal) passes
// it through the eigenvector of the best-fit plane:
//   n = s·e₀,  de₀ = −P dC e₀,  P = Σ_{m=1,2} e_m e_mᵀ/(λ_m − λ₀),
//   dC = Σ_p (dr_p r_pᵀ + r_p dr_pᵀ),  r_p = x_p − x̄,
// so cᵀdn = Σ_p [w (r_p·e₀) + e₀ (w·r_p)]·dx_p with w = −s P c (the mean drops
// out because Σ_p r_p = 0).
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "models/yarn/contact_normals.h"
#include "models/yarn/terms/bending.h"
#include "models/yarn/terms/stretch.h"

namespace wl {

void ContactNormals::compute_gradient(const Vec& q) {
  if (!all_active_) throw std::invalid_argument("ContactNormals::compute_gradient: F_n is computed at some nodes only");
  if (q.size() != grid_.num_dofs()) {
    std::ostringstream msg;
    msg << "ContactNormals::compute_gradient: state has " << q.size() << " entries, expected " << grid_.num_dofs();
    throw std::invalid_argument(msg.str());
  }
  if (stretch_ != NormalForceStretch::crimped_copies)
    throw std::invalid_argument(
        "ContactNormals::compute_gradient: the exact derivatives of F_n exist for the stretch on the crimped "
        "copies only (compat.normal_force_stretch = \"crimped\")");
  if (bending_at_rest_)
    throw std::invalid_argument(
        "ContactNormals::compute_gradient: the exact derivatives of F_n exist for the current sliding coordinates "
        "only (compat.normal_force_bending_uv = \"current\")");
  const int nu = grid_.nu(), nv = grid_.nv(), N = grid_.num_nodes();
  grad_.resize(N);
  parts_.assign(N, StiffnessParts{});
  // Adjoints per node of one stencil: crimped warp / weft copies, normal, x, u, v.
  std::vector<Vec3> bw(N), bf(N), bn(N), bx(N);
  std::vector<double> bu(N), bv(N);
  std::vector<char> mark(N, 0), mark_u(N, 0), mark_v(N, 0);
  std::vector<int> touched;
  auto touch = [&](int k) {
    if (mark[k]) return;
    mark[k] = 1;
    touched.push_back(k);
    bw[k] = bf[k] = bn[k] = bx[k] = Vec3::Zero();
    bu[k] = bv[k] = 0.0;
  };

  // One yarn's elements that put force on `id`: adjoint `adj` of that force.
  // along(k): the node k steps along the yarn (clamped by the caller); xc: the
  // crimped copy; s: its coordinate; b/bs/ms: where the adjoints go.
  struct YarnSide {
    const std::vector<Vec3>& xc;
    const std::vector<double>& s;
    std::vector<Vec3>& b;
    std::vector<double>& bs;
    std::vector<char>& ms;
    double ks, kb;
  };
  auto yarn = [&](const YarnSide& y, const int* line, int count, int pos, const Vec3& adj, double& stretch_part,
                  double& bending_part) {
    Eigen::Matrix<double, 8, 1> fs;
    Eigen::Matrix<double, 8, 8> Ks;
    for (int a = pos - 1; a <= pos; ++a) {  // segments (a, a+1) containing pos
      if (a < 0 || a + 1 >= count) continue;
      const int na = line[a], nb = line[a + 1];
      double lq[8];
      for (int c = 0; c < 3; ++c) lq[c] = y.xc[na][c], lq[3 + c] = y.xc[nb][c];
      lq[6] = y.s[na], lq[7] = y.s[nb];
      StretchTerm::local_evaluate(lq, y.ks, fs.data(), Ks.data());
      const int r0 = (a == pos) ? 0 : 3;
      stretch_part += adj.dot(fs.segment<3>(r0));
      const Eigen::Matrix<double, 8, 1> g = Ks.middleRows<3>(r0).transpose() * adj;
      touch(na), touch(nb);
      y.b[na] += g.segment<3>(0), y.b[nb] += g.segment<3>(3);
      y.bs[na] += g[6], y.bs[nb] += g[7];
      y.ms[na] = y.ms[nb] = 1;
    }
    Eigen::Matrix<double, 11, 1> fb;
    Eigen::Matrix<double, 11, 11> Kb;
    for (int c = pos - 1; c <= pos + 1; ++c) {  // bending stencils (c, c+1, c−1) containing pos
      if (c < 1 || c + 1 >= count) continue;
      const int n0 = line[c], n1 = line[c + 1], n2 = line[c - 1];
      double lq[11];
      for (int k = 0; k < 3; ++k) lq[k] = y.xc[n0][k], lq[3 + k] = y.xc[n1][k], lq[6 + k] = y.xc[n2][k];
      lq[9] = y.s[n1], lq[10] = y.s[n2];
      BendingTerm::local_evaluate(lq, y.kb, fb.data(), Kb.data());
      const int r0 = pos == c ? 0 : (pos == c + 1 ? 3 : 6);
      bending_part += adj.dot(fb.segment<3>(r0));
      const Eigen::Matrix<double, 11, 1> g = Kb.middleRows<3>(r0).transpose() * adj;
      touch(n0), touch(n1), touch(n2);
      y.b[n0] += g.segment<3>(0), y.b[n1] += g.segment<3>(3), y.b[n2] += g.segment<3>(6);
      y.bs[n1] += g[9], y.bs[n2] += g[10];
      y.ms[n1] = y.ms[n2] = 1;
    }
  };

  std::vector<int> warp_line(nu), weft_line(nv);
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int id = grid_.node(i, j);
      GradientRow& row = grad_[id];
      row.dof.clear();
      row.value.clear();
      if (!grid_.interior(i, j)) continue;  // F_n = 0 on the outer ring
      for (int k : touched) mark[k] = mark_u[k] = mark_v[k] = 0;
      touched.clear();
      touch(id);
      for (int k = 0; k < nu; ++k) warp_line[k] = grid_.node(k, j);
      for (int k = 0; k < nv; ++k) weft_line[k] = grid_.node(i, k);
      const Vec3 a = 0.5 * n_[id];
      StiffnessParts part;
      yarn({xw_, u_, bw, bu, mark_u, warp_ks_[j], warp_kb_[j]}, warp_line.data(), nu, i, a, part.warp_stretch,
           part.warp_bending);
      yarn({xf_, v_, bf, bv, mark_v, weft_ks_[i], weft_kb_[i]}, weft_line.data(), nv, j, -a, part.weft_stretch,
           part.weft_bending);
      bn[id] += 0.5 * (fu_[id] - fv_[id]);
      // Crimp: x_k ∓ R n_k.
      const size_t crimped = touched.size();
      for (size_t t = 0; t < crimped; ++t) {
        const int k = touched[t];
        bx[k] += bw[k] + bf[k];
        bn[k] += R_ * (bf[k] - bw[k]);
      }
      // Normals: eigenvector of the best-fit plane of each crimped node.
      for (size_t t = 0; t < crimped; ++t) {
        const int k = touched[t];
        const Vec3 e0 = eig_vec_[k].col(0);
        Vec3 w = Vec3::Zero();
        if (!fallback_[k])
          for (int m = 1; m < 3; ++m) {
            const double gap = eig_val_[k][m] - eig_val_[k][0];
            if (gap > 0.0) w -= eig_sign_[k] * eig_vec_[k].col(m) * (eig_vec_[k].col(m).dot(bn[k]) / gap);
          }
        Vec3 mean = Vec3::Zero();
        int count = 0;
        for (int p : fit_points_[k])
          if (p >= 0) mean += x_[p], ++count;
        mean /= count;
        for (int p : fit_points_[k])
          if (p >= 0) {
            const Vec3 r = x_[p] - mean;
            touch(p);
            bx[p] += w * r.dot(e0) + e0 * w.dot(r);
          }
      }
      const double g = 0.5 * n_[id].dot(fu_[id] - fv_[id]);
      const double active = g > 0.0 ? 1.0 : 0.0;
      for (int k : touched) {
        const NodeDofs& d = grid_.dofs(k);
        for (int c = 0; c < 3; ++c) row.dof.push_back(d.x + c), row.value.push_back(active * bx[k][c]);
        if (mark_u[k] && is_dof(d.u)) row.dof.push_back(d.u), row.value.push_back(active * bu[k]);
        if (mark_v[k] && is_dof(d.v)) row.dof.push_back(d.v), row.value.push_back(active * bv[k]);
      }
      part.warp_stretch *= active, part.warp_bending *= active;
      part.weft_stretch *= active, part.weft_bending *= active;
      parts_[id] = part;
    }
  for (int k : touched) mark[k] = mark_u[k] = mark_v[k] = 0;
}

}  // namespace wl
