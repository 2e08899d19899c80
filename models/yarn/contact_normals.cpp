#include "models/yarn/contact_normals.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "models/yarn/terms/bending.h"
#include "models/yarn/terms/stretch.h"

namespace wl {
namespace {

void check_stiffness(const std::vector<double>& k, int expected, const char* what) {
  std::ostringstream msg;
  if (static_cast<int>(k.size()) != expected) {
    msg << "ContactNormals: " << what << " has " << k.size() << " entries, expected " << expected;
    throw std::invalid_argument(msg.str());
  }
  for (size_t i = 0; i < k.size(); ++i)
    if (!std::isfinite(k[i]) || k[i] < 0.0) {
      msg << "ContactNormals: " << what << "[" << i << "] = " << k[i] << ", expected a finite value >= 0";
      throw std::invalid_argument(msg.str());
    }
}

double coordinate(const Vec& q, const Vec& constants, int index) {
  return is_dof(index) ? q[index] : constants[constant_slot(index)];
}

}  // namespace

ContactNormals::ContactNormals(const WovenGrid& grid, std::vector<double> warp_ks, std::vector<double> warp_kb,
                               std::vector<double> weft_ks, std::vector<double> weft_kb, double radius,
                               NormalForceStretch stretch, bool bending_at_rest)
    : grid_(grid),
      warp_ks_(std::move(warp_ks)),
      warp_kb_(std::move(warp_kb)),
      weft_ks_(std::move(weft_ks)),
      weft_kb_(std::move(weft_kb)),
      R_(radius),
      stretch_(stretch),
      bending_at_rest_(bending_at_rest) {
  if (grid_.nu() < 2 || grid_.nv() < 2) {
    std::ostringstream msg;
    msg << "ContactNormals: grid of " << grid_.nu() << " x " << grid_.nv() << " nodes, expected at least 2 x 2";
    throw std::invalid_argument(msg.str());
  }
  check_stiffness(warp_ks_, grid_.nv(), "warp_ks");
  check_stiffness(warp_kb_, grid_.nv(), "warp_kb");
  check_stiffness(weft_ks_, grid_.nu(), "weft_ks");
  check_stiffness(weft_kb_, grid_.nu(), "weft_kb");
  if (!std::isfinite(radius) || radius <= 0.0) {
    std::ostringstream msg;
    msg << "ContactNormals: radius = " << radius << " m, expected a finite value > 0";
    throw std::invalid_argument(msg.str());
  }
  const size_t n = grid_.num_nodes();
  x_.assign(n, Vec3::Zero());
  n_ = xw_ = xf_ = fu_ = fv_ = eig_val_ = x_;
  u_.assign(n, 0.0);
  v_ = fn_ = eig_sign_ = u_;
  eig_vec_.assign(n, Mat3::Zero());
  fit_points_.assign(n, {-1, -1, -1, -1, -1});
  fallback_.assign(n, 0);
  active_.assign(n, 1);
  fitted_ = active_;
}

void ContactNormals::set_active(std::vector<char> active) {
  if (static_cast<int>(active.size()) != grid_.num_nodes())
    throw std::invalid_argument("ContactNormals::set_active: " + std::to_string(active.size()) + " entries, expected " +
                                std::to_string(grid_.num_nodes()));
  active_ = std::move(active);
  all_active_ = std::all_of(active_.begin(), active_.end(), [](char a) { return a != 0; });
  fitted_.assign(active_.size(), 0);
  const int nu = grid_.nu(), nv = grid_.nv();
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      if (!active_[grid_.node(i, j)]) continue;
      for (int d = -2; d <= 2; ++d) {  // the crimped copies its segments and bending stencils reach
        if (i + d >= 0 && i + d < nu) fitted_[grid_.node(i + d, j)] = 1;
        if (j + d >= 0 && j + d < nv) fitted_[grid_.node(i, j + d)] = 1;
      }
    }
  std::fill(fn_.begin(), fn_.end(), 0.0);
}

void ContactNormals::compute(const Vec& q) {
  if (q.size() != grid_.num_dofs()) {
    std::ostringstream msg;
    msg << "ContactNormals::compute: state has " << q.size() << " entries, expected " << grid_.num_dofs();
    throw std::invalid_argument(msg.str());
  }
  const int nu = grid_.nu(), nv = grid_.nv();
  const Vec& constants = grid_.constants();
  for (int id = 0; id < grid_.num_nodes(); ++id) {
    const NodeDofs& d = grid_.dofs(id);
    x_[id] = q.segment<3>(d.x);
    u_[id] = coordinate(q, constants, d.u);
    v_[id] = coordinate(q, constants, d.v);
  }

  const bool on_centre_lines = stretch_ == NormalForceStretch::centre_lines;
  // Normals: best-fit plane of the node and its grid neighbours (docs/models.md §3.6).
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int id = grid_.node(i, j);
      if (!fitted_[id]) continue;
      const int ip = grid_.node(std::min(i + 1, nu - 1), j), im = grid_.node(std::max(i - 1, 0), j);
      const int jp = grid_.node(i, std::min(j + 1, nv - 1)), jm = grid_.node(i, std::max(j - 1, 0));
      const int pts[5] = {id, ip, im, jp, jm};
      bool use[5] = {true, ip != id, im != id, jp != id, jm != id};
      Vec3 mean = Vec3::Zero();
      int count = 0;
      for (int k = 0; k < 5; ++k)
        if (use[k]) mean += x_[pts[k]], ++count;
      mean /= count;
      Mat3 scatter = Mat3::Zero();
      for (int k = 0; k < 5; ++k)
        if (use[k]) {
          const Vec3 r = x_[pts[k]] - mean;
          scatter += r * r.transpose();
        }
      const Vec3 orient = (x_[ip] - x_[im]).cross(x_[jp] - x_[jm]);
      Eigen::SelfAdjointEigenSolver<Mat3> eig(scatter, Eigen::ComputeEigenvectors);
      Vec3 n = eig.eigenvectors().col(0);
      // Points on a line (no unique plane): fall back to the orientation vector.
      const double on = orient.norm();
      fallback_[id] = eig.eigenvalues()[1] <= 1e-12 * eig.eigenvalues()[2] && on > 0.0;
      if (fallback_[id]) n = orient / on;
      const double flip = n.dot(orient) < 0.0 ? -1.0 : 1.0;
      n_[id] = static_cast<double>(grid_.sign(i, j)) * flip * n;
      eig_vec_[id] = eig.eigenvectors();
      eig_val_[id] = eig.eigenvalues();
      eig_sign_[id] = static_cast<double>(grid_.sign(i, j)) * flip;
      for (int k = 0; k < 5; ++k) fit_points_[id][k] = use[k] ? pts[k] : -1;
      // Crimped copies (docs/models.md §5.3); the published code leaves the ring where it is.
      const double offset = on_centre_lines && !grid_.interior(i, j) ? 0.0 : R_;
      xw_[id] = x_[id] - offset * n_[id];  // crimped warp copy
      xf_[id] = x_[id] + offset * n_[id];  // crimped weft copy
      fu_[id].setZero();
      fv_[id].setZero();
    }

  // The sliding coordinates the bending of the copies sees: the current ones, or those at rest.
  const double L = grid_.spacing();
  const auto bend_u = [&](int id) { return bending_at_rest_ ? (id % nu) * L : u_[id]; };
  const auto bend_v = [&](int id) { return bending_at_rest_ ? (id / nu) * L : v_[id]; };
  // F^u: stretch and bending of every warp on its crimped copy (stretch on the centre line with
  // centre_lines), accumulated per node.
  const std::vector<Vec3>& warp_stretch_at = on_centre_lines ? x_ : xw_;
  const std::vector<Vec3>& weft_stretch_at = on_centre_lines ? x_ : xf_;
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i + 1 < nu; ++i) {
      const int a = grid_.node(i, j), b = grid_.node(i + 1, j);
      if (!active_[a] && !active_[b]) continue;
      const auto f = StretchTerm::local_force(warp_stretch_at[a], warp_stretch_at[b], u_[a], u_[b], warp_ks_[j]);
      fu_[a] += f.segment<3>(0);
      fu_[b] += f.segment<3>(3);
    }
    for (int i = 1; i + 1 < nu; ++i) {
      const int c = grid_.node(i, j), nx = grid_.node(i + 1, j), pv = grid_.node(i - 1, j);
      if (!active_[c] && !active_[nx] && !active_[pv]) continue;
      const auto f = BendingTerm::local_force(xw_[c], xw_[nx], xw_[pv], bend_u(nx), bend_u(pv), warp_kb_[j]);
      fu_[c] += f.segment<3>(0);
      fu_[nx] += f.segment<3>(3);
      fu_[pv] += f.segment<3>(6);
    }
  }
  // F^v: the same for every weft along v.
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j + 1 < nv; ++j) {
      const int a = grid_.node(i, j), b = grid_.node(i, j + 1);
      if (!active_[a] && !active_[b]) continue;
      const auto f = StretchTerm::local_force(weft_stretch_at[a], weft_stretch_at[b], v_[a], v_[b], weft_ks_[i]);
      fv_[a] += f.segment<3>(0);
      fv_[b] += f.segment<3>(3);
    }
    for (int j = 1; j + 1 < nv; ++j) {
      const int c = grid_.node(i, j), nx = grid_.node(i, j + 1), pv = grid_.node(i, j - 1);
      if (!active_[c] && !active_[nx] && !active_[pv]) continue;
      const auto f = BendingTerm::local_force(xf_[c], xf_[nx], xf_[pv], bend_v(nx), bend_v(pv), weft_kb_[i]);
      fv_[c] += f.segment<3>(0);
      fv_[nx] += f.segment<3>(3);
      fv_[pv] += f.segment<3>(6);
    }
  }

  // F_n = ReLU(½ nᵀ(F^u − F^v)), Gong et al. 2022 eq. (3); zero on the outer ring.
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int id = grid_.node(i, j);
      fn_[id] = grid_.interior(i, j) && active_[id] ? std::max(0.0, 0.5 * n_[id].dot(fu_[id] - fv_[id])) : 0.0;
    }
}

}  // namespace wl
