// The continuum of a knit scene (docs/models.md §11.9): the contact grid's
// mesh, the yarn level's mass, pins and handles at the contacts' vertices, a
// calibration's parameter file used as written, and what cannot map refused.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "models/fem/fem_model.h"
#include "models/fem/knit_contact_mesh.h"
#include "models/knit/knit_model.h"
#include "tests/output/output_test_util.h"

namespace wl {
namespace {

const std::string kStiffnesses =
    "warp_stretch_N_per_m = 40.0\nweft_stretch_N_per_m = 50.0\nshear_N_per_m = 2.0\n"
    "warp_bending_N_m = 1e-6\nweft_bending_N_m = 2e-6\n";

// A small upright stockinette with calibrated-looking [fem] stiffnesses and `extra` appended.
std::string knit_toml(int courses, int wales, const std::string& extra, bool sliding = true) {
  return "[cloth]\nspacing_m = 2e-3\nradius_m = 2e-4\nsliding = " + std::string(sliding ? "true" : "false") +
         "\n[cloth.pattern]\nkind = \"stockinette\"\ncourses = " + std::to_string(courses) +
         "\nwales = " + std::to_string(wales) +
         "\ncourse_spacing_m = 1.6e-3\n[pose]\nkind = \"upright\"\nheight_m = 0.05\n" + extra;
}
Scene knit(int courses, int wales, const std::string& extra = "[fem]\n" + kStiffnesses, bool sliding = true) {
  return parse_scene(knit_toml(courses, wales, extra, sliding), "knit.toml");
}

// The mass a model moves under a rigid translation along x: 1ᵀM1 over the x position DoFs.
double translational_mass(Model& model, const std::vector<int>& x_dofs) {
  Evaluation ev;
  allocate_evaluation(model, ev);
  model.evaluate(0.0, model.initial_q(), model.initial_v(), kMass, ev);
  Vec e = Vec::Zero(model.num_dofs());
  for (int x : x_dofs) e[x] = 1.0;
  return e.dot(ev.mass * e);
}

// The continuum carries the yarn level's mass (its segments' inertia), at every stride the grid takes.
TEST(KnitContinuum, CarriesTheYarnLevelsMass) {
  for (bool sliding : {true, false}) {
    const Scene s = knit(6, 5, "[fem]\nstride = 3\n" + kStiffnesses, sliding);  // 9 column and 6 row spacings
    KnitModel yarn(s);
    std::vector<int> x_dofs;
    for (const KnitNode& n : yarn.graph().nodes()) x_dofs.push_back(n.x_dof);
    const double m_yarn = translational_mass(yarn, x_dofs);
    ASSERT_GT(m_yarn, 0.0);
    for (int stride : {1, 3}) {
      Scene t = s;
      t.fem.stride = stride;
      FemModel fem(t);
      std::vector<int> vertex_x;
      for (int v = 0; v < fem.mesh().num_vertices(); ++v) vertex_x.push_back(3 * v);
      EXPECT_NEAR(translational_mass(fem, vertex_x), m_yarn, 1e-12 * m_yarn) << "stride " << stride;
      double sum = 0;
      for (double m : fem.vertex_mass()) sum += m;
      EXPECT_NEAR(sum, m_yarn, 1e-12 * m_yarn);
    }
  }
}

// Vertex (κ, ρ) at material (κW/2, ρC) and at the contact's generated place, posed as the yarn
// level poses its nodes: upright, row 0 on top. A pin holds the contact's vertex, a handle pulls it.
TEST(KnitContinuum, TheContactGridMeshAndItsBoundary) {
  const Scene s = knit(4, 3, "[fem]\n" + kStiffnesses + "[[pins]]\nnode = [0, 5]\n[[handles]]\nnode = [4, 2]\n");
  FemModel fem(s);
  const FemMesh& m = fem.mesh();
  ASSERT_EQ(m.num_vertices(), 6 * 5);
  EXPECT_EQ(m.num_triangles(), 2 * 5 * 4);
  const double W = 2e-3, C = 1.6e-3;
  const int v = m.grid_vertex(5, 0);
  EXPECT_NEAR((m.uv[v] - Vec2(5 * W / 2, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((m.x[v] - Vec3(5 * W / 2 - W / 4, 0.0, 0.05 + C / 2)).norm(), 0.0, 1e-15);
  EXPECT_EQ(fem.vertex_of_node(NodeRef{0, 5}), v);
  EXPECT_EQ(fem.vertex_of_node(NodeRef{4, 2}), m.grid_vertex(2, 4));
  const std::span<const int> fixed = fem.fixed_dofs();
  ASSERT_EQ(fixed.size(), 3u);
  EXPECT_EQ(fixed[0], 3 * v);
  // Of the knit's contacts (their nodes' midpoints, moved by the relaxed tile), contact (0, 5)
  // is the one nearest the vertex.
  const KnitModel yarn(s);
  const std::vector<KnitGridContact> contacts = knit_grid_contacts(yarn.graph());
  int nearest = -1;
  double best = 1e300;
  for (size_t k = 0; k < contacts.size(); ++k) {
    const Vec3 mid =
        0.5 * (yarn.position(yarn.initial_q(), contacts[k].a) + yarn.position(yarn.initial_q(), contacts[k].b));
    if ((mid - m.x[v]).norm() < best) best = (mid - m.x[v]).norm(), nearest = static_cast<int>(k);
  }
  EXPECT_EQ(nearest, 5);
  int handles = 0;
  for (const auto& t : fem.terms())
    if (t->name() == "handles") {
      ASSERT_EQ(t->num_elements(), 1);
      EXPECT_EQ(t->stencil(0)[0], 3 * m.grid_vertex(2, 4));
      ++handles;
    }
  EXPECT_EQ(handles, 1);
}

// A knit calibration's params.toml is used as written, its areal density (the calibration
// patch's) replaced by the scene's own yarn mass per area.
TEST(KnitContinuum, ReadsACalibrationsParameterFile) {
  test::ScratchDir dir;
  std::ofstream(dir / "params.toml") << "areal_density_kg_per_m2 = 123.0\n"
                                     << kStiffnesses << "shear_lock_angle_rad = 1.2\nshear_lock_exponent = 3\n";
  std::ofstream(dir / "knit.toml") << knit_toml(4, 3, "[fem]\nparameter_file = \"params.toml\"\n");
  const Scene s = load_scene((dir / "knit.toml").string());
  const FemMaterial m = fem_material(s);
  EXPECT_EQ(m.warp_stretch_N_per_m, 40.0);
  EXPECT_EQ(m.weft_bending_N_m, 2e-6);
  EXPECT_EQ(m.shear_lock_angle_rad, 1.2);
  EXPECT_NEAR(m.areal_density_kg_per_m2, knit_yarn_mass(s) / knit_contact_grid(s).area(), 1e-15);
}

// What has no knit counterpart is a located error naming the key.
TEST(KnitContinuum, RefusesWhatCannotMap) {
  struct Case {
    std::string extra, key;
    int line;
  } cases[] = {
      {"[fem]\nstride = 2\n", "fem.stride", 14},  // 2·wales − 1 = 5 is odd
      {"[fem]\nborder_strip = true\n", "fem.border_strip", 14},
      {"[fem]\ngrid_line_bending = true\n", "fem.grid_line_bending", 14},
      {"[fem]\nyarn_node_mass = true\n", "fem.yarn_node_mass", 14},
      {"[fem]\nareal_density_kg_per_m2 = 0.5\n", "fem.areal_density_kg_per_m2", 14},
  };
  for (const Case& c : cases) {
    try {
      knit(4, 3, c.extra);
      ADD_FAILURE() << c.key << " should be refused";
    } catch (const SceneError& e) {
      EXPECT_EQ(e.key, c.key);
      EXPECT_EQ(e.line, c.line) << e.what();
    }
  }
  try {  // the yarn damper has no edge to act on
    FemModel fem(knit(4, 3, "[fem]\n" + kStiffnesses + "[damping]\nyarn_viscosity_Pa_s = 10.0\n"));
    ADD_FAILURE() << "a damped knit's continuum should be refused";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key, "damping.yarn_viscosity_Pa_s");
    EXPECT_EQ(e.line, 20);
  }
  try {  // no stiffness without a calibration
    FemModel fem(knit(4, 3, "[fem]\nwarp_stretch_N_per_m = 40.0\n"));
    ADD_FAILURE() << "a knit's continuum without its stiffnesses should be refused";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key, "fem.weft_stretch_N_per_m");
    EXPECT_EQ(e.line, 13);  // the [fem] table
  }
}

}  // namespace
}  // namespace wl
