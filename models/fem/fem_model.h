// The continuum triangle-FEM model (docs/models.md §6): the cloth of a
// Scene as a triangle mesh (fem_mesh.h) with 3 DoFs per vertex (x at 3·vertex),
// material from fem_material.h, and one term per idea (models/fem/terms/):
//   stretch  → WarpWeftStretchTerm       bending → HingeBendingTerm (interior edges)
//   shear    → InPlaneShearTerm (lock)   gravity → NodalGravityTerm
//   wind     → WindTerm (models/common, as the yarn model, per triangle)
//   handles  → HandleSpringTerm (models/common) at the handle's vertex
//   a tile law ([fem] tile_law, docs/models.md §6.9) → TileMembraneTerm instead of
//            stretch and shear, TileBendingTerm (per triangle) instead of the bending
// The lumped mass (LumpedMassTerm) is always present: the FEM has no other
// inertia, so terms.inertia does not apply; mass is constant. Its vertex
// shares are a third of each triangle's, or follow the yarn level's node masses.
// Pins and handles (crossing (i, j)) map to the vertex at material (iL, jL).
// Scenes validate that, with stride > 1, they lie on the stride lattice, so a
// grid mesh always has that vertex; a mesh file uses the nearest vertex in UV
// and rejects a point farther than the mesh's longest UV edge (outside the mesh).
#pragma once
#include <array>
#include <map>

#include "models/common/obstacle_contact.h"
#include "models/core/term_model.h"
#include "models/fem/deformation_gradient.h"
#include "models/fem/fem_material.h"
#include "models/fem/fem_mesh.h"
#include "models/fem/tension_map.h"
#include "models/scene/scene.h"

namespace wl {

// The yarn level's lumped node masses at every crossing (index i + wefts·j) [kg]: half of each
// yarn segment at the crossing, warp and weft ([fem] yarn_node_mass, docs/models.md §6.6).
std::vector<double> yarn_node_masses(const Scene& scene);

class FemModel : public TermModel {
 public:
  explicit FemModel(const Scene& scene);
  // With an explicit mesh and material (calibration, tests).
  FemModel(const Scene& scene, FemMesh mesh, const FemMaterial& material);

  std::unique_ptr<Model> clone() const override { return std::make_unique<FemModel>(*this); }
  // Re-parameterizes the model: its terms as a model built with `material`
  // would have them, on the same mesh, pattern and assembly (calibration's
  // curve evaluations, docs/calibration.md §4). Evaluations are then bitwise
  // those of FemModel(scene, mesh, material).
  void set_material(const FemMaterial& material);
  std::string name() const override { return "fem"; }
  bool mass_depends_on_q() const override { return false; }
  Frame frame(double t, const Vec& q, const Vec& v) const override;
  Frame obstacle_frame(double t) const override;
  std::map<std::string, std::string> describe() const override;

  const FemMesh& mesh() const { return mesh_; }
  const FemMaterial& material() const { return material_; }
  const std::vector<Hinge>& hinges() const { return hinges_; }
  // Lumped mass of each vertex [kg] (sum of ρ_A·A/3 over its triangles).
  const std::vector<double>& vertex_mass() const { return vertex_mass_; }
  Vec3 position(const Vec& q, int vertex) const { return q.segment<3>(3 * vertex); }
  // Vertex carrying crossing (i, j) (material (iL, jL)); see above.
  int vertex_of_node(const NodeRef& node) const;
  // The deformed surface at material point uv (linear interpolation in the
  // triangle that contains it); false when uv lies outside the mesh.
  bool surface_point(const Vec& q, const Vec2& uv, Vec3* x) const;
  // The same point as weights w of the vertices v of its triangle: x = Σ w_i x(v_i).
  bool surface_weights(const Vec2& uv, std::array<int, 3>* vertices, Vec3* weights) const;
  // Optitex tension map per triangle (tension_map.h) at state q.
  std::vector<FaceTension> tension_map(const Vec& q) const;

 private:
  void build();
  // The terms from material_ into `terms` (terms_, or set_material's
  // replacements); each add_* builds one term when the scene turns it on.
  void add_terms(std::vector<std::unique_ptr<Term>>& terms);
  void add_mass(std::vector<std::unique_ptr<Term>>& terms);  // sets vertex_mass_
  void add_stretch(std::vector<std::unique_ptr<Term>>& terms) const;
  void add_shear(std::vector<std::unique_ptr<Term>>& terms) const;
  void add_border_stretch(std::vector<std::unique_ptr<Term>>& terms) const;
  void add_grid_line_bending(std::vector<std::unique_ptr<Term>>& terms) const;
  void add_hinge_bending(std::vector<std::unique_ptr<Term>>& terms) const;
  void add_gravity(std::vector<std::unique_ptr<Term>>& terms) const;  // reads vertex_mass_
  void add_wind(std::vector<std::unique_ptr<Term>>& terms) const;
  void add_damping(std::vector<std::unique_ptr<Term>>& terms) const;
  void add_handles(std::vector<std::unique_ptr<Term>>& terms) const;
  void add_obstacles(std::vector<std::unique_ptr<Term>>& terms);  // sets obstacles_
  void add_self_contact(std::vector<std::unique_ptr<Term>>& terms) const;

  Scene scene_;
  FemMesh mesh_;
  FemMaterial material_;
  std::vector<Hinge> hinges_;
  std::vector<double> vertex_mass_;
  std::vector<TriangleRest> rest_;         // per triangle, from the rest UVs
  std::vector<double> rest_lu_, rest_lv_;  // per triangle, from the initial positions
  double max_uv_edge_ = 0.0;
  ObstacleContact obstacles_;  // rigid obstacles of the scene (docs/models.md §3.11)
};

}  // namespace wl
