// Basic numeric types shared by every model and integrator. SI units throughout.
#pragma once
#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace wl {

using Vec = Eigen::VectorXd;
using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

// The matrix [a]x with [a]x b = a x b.
inline Mat3 cross_matrix(const Vec3& a) {
  Mat3 m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// A stencil entry that is not a degree of freedom (a border node's frozen u, or
// every u and v when sliding is off) is stored as ~k: an index into the model's
// table of constant coordinates. Its velocity is zero.
inline bool is_dof(int index) { return index >= 0; }
inline int constant_slot(int index) { return ~index; }
inline int encode_constant(int slot) { return ~slot; }

}  // namespace wl
