// Contact normal n and normal force F_n at every crossing of the woven grid,
// docs/models.md §3.6 (Gong et al. 2022 eq. (3), §3.3) with the crimp of docs/models.md §5.3.
//
//   n    smallest-eigenvalue eigenvector of Σ(x_k − x̄)(x_k − x̄)ᵀ over the node
//        and its (up to) 4 grid neighbours (best-fit plane), oriented along
//        n_plane = (x_{i+1,j} − x_{i−1,j}) × (x_{i,j+1} − x_{i,j−1}) (the
//        +u × +v direction: +z for a sheet x = (iL, jL, 0)), then multiplied by
//        s_ij = grid.sign(i, j), so it points from warp to weft (docs/models.md §2.3).
//        Ring nodes use the same fit with the neighbours they have, and
//        one-sided differences in n_plane (a missing neighbour is replaced by
//        the node itself).
//   F_n  = ReLU(½ nᵀ(F^u − F^v)), where F^u is the total stretch + bending force
//        on the node from its warp, evaluated on the crimped copy of that warp
//        (every warp node k moved to x_k − R n_k), and F^v the same from its
//        weft with nodes at x_k + R n_k. "Total" means every stretch segment and
//        bending stencil of that yarn containing the node (two segments, up to
//        three bending stencils). F_n = 0 on the outer ring.
//
// compute() allocates nothing and costs O(nodes). compute_gradient() adds the
// exact derivatives (docs/models.md §3.6.1): ∂F_n/∂q as a sparse row per node
// over a fixed stencil (the node's own plus two grid steps along its yarns and
// the normals' neighbours), and the parts of F_n proportional to each yarn's
// k_s and k_b, which give ∂F_n/∂Y and ∂F_n/∂B.
#pragma once
#include <array>
#include <vector>

#include "models/core/types.h"
#include "models/yarn/woven_grid.h"

namespace wl {

// Where the stretch part of F^u and F^v is evaluated: on the crimped copies (the lab's model,
// docs/models.md §5.3), or on the actual centre lines with the outer ring left uncrimped and only
// bending on the crimped copies (the authors' published code, docs/published_code.md rows 1–2).
enum class NormalForceStretch { crimped_copies, centre_lines };

class ContactNormals {
 public:
  // warp_* indexed by warp j (size grid.nv()), weft_* by weft i (size grid.nu());
  // k_s = Y·πR² (N), k_b = B·πR²; radius R (m). Throws std::invalid_argument on
  // wrong sizes, negative/non-finite stiffness or non-positive radius.
  ContactNormals(const WovenGrid& grid, std::vector<double> warp_ks, std::vector<double> warp_kb,
                 std::vector<double> weft_ks, std::vector<double> weft_kb, double radius,
                 NormalForceStretch stretch = NormalForceStretch::crimped_copies, bool bending_at_rest = false);
  // bending_at_rest: the bending of the crimped copies with the sliding coordinates at rest (u = iL,
  // v = jL), as the published code computes it (docs/published_code.md row 24).

  // q: the full state (size grid.num_dofs()); frozen u/v come from grid.constants().
  void compute(const Vec& q);
  // F_n, F^u and F^v only at the nodes marked (per node id; a mixed cloth's region, docs/models.md
  // §12.2): compute() then fits normals only within two grid steps of them, which their crimped
  // yarns reach, and F_n is 0 elsewhere. Default: every node. Throws std::invalid_argument on a
  // wrong size; compute_gradient() needs every node.
  void set_active(std::vector<char> active);

  const std::vector<double>& normal_force() const { return fn_; }  // per node id
  const std::vector<Vec3>& normal() const { return n_; }           // per node id, unit, warp → weft
  // Forces on each node from its warp (F^u) and weft (F^v) on the crimped copies.
  const std::vector<Vec3>& warp_force() const { return fu_; }
  const std::vector<Vec3>& weft_force() const { return fv_; }

  // After compute(q): ∂F_n/∂q of every node (crimped_copies only: throws
  // std::invalid_argument for centre_lines) (zero where F_n = 0). The entries
  // of a node's row are always the same DoFs in the same order (zeros kept),
  // so a caller can map them to matrix slots once.
  struct GradientRow {
    std::vector<int> dof;
    std::vector<double> value;
  };
  void compute_gradient(const Vec& q);
  const std::vector<GradientRow>& gradient() const { return grad_; }
  // Parts of F_n (before the ReLU, zero where F_n = 0) proportional to the
  // warp's k_s, the warp's k_b, the weft's k_s and the weft's k_b of the node:
  // ∂F_n/∂k = part/k. Valid after compute_gradient().
  struct StiffnessParts {
    double warp_stretch = 0.0, warp_bending = 0.0, weft_stretch = 0.0, weft_bending = 0.0;
  };
  const std::vector<StiffnessParts>& stiffness_parts() const { return parts_; }

 private:
  WovenGrid grid_;
  std::vector<double> warp_ks_, warp_kb_, weft_ks_, weft_kb_;
  double R_;
  NormalForceStretch stretch_;
  bool bending_at_rest_;
  std::vector<Vec3> x_, n_, xw_, xf_, fu_, fv_;
  std::vector<double> u_, v_, fn_;
  // Per node: eigenvectors (columns, ascending eigenvalues) and eigenvalues of
  // the scatter, the points it was fitted to and the sign n = sign·e₀.
  std::vector<Mat3> eig_vec_;
  std::vector<Vec3> eig_val_;
  std::vector<std::array<int, 5>> fit_points_;  // node ids, −1 unused
  std::vector<double> eig_sign_;
  std::vector<char> fallback_;         // n from the orientation vector (points on a line)
  std::vector<char> active_, fitted_;  // per node: F_n wanted; normal and crimped copies needed
  bool all_active_ = true;
  std::vector<GradientRow> grad_;
  std::vector<StiffnessParts> parts_;
};

}  // namespace wl
