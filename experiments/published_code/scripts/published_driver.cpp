// Driver for the authors' published yarn-level code (Gong et al. 2022), written for the
// published_code study. It is compiled by build_published.py against the authors' sources,
// which that script fetches into a scratch folder outside this repository; nothing of theirs
// is stored here. It runs their homogeneous hanging cloth (every yarn Yarn1, plain weave,
// upright pose, two top corners on penalty springs, wind along +y, implicit Euler with their
// own assembly; h = 1 ms and their own linear solver unless told otherwise) and writes, as CSV:
//   trajectory.csv  step,time_s,i,j,x,y,z,u,v,vx,vy,vz,udot,vdot,u_anchor,v_anchor
//                   every step (the sliding columns are empty on the ring)
//   forces.csv      step,term,i,j,fx,fy,fz,fu,fv     each term's generalized force at the
//                                                      requested steps, before the solve
//                                                      (term normal_force: F_n in fx)
//   jacobians.csv   step,wrt,rows,relative_error,fd_norm   their assembled dF/dq and dF/dv times a
//                   random direction of one block of DoFs (wrt: x, uv, vx, vuv) against central
//                   differences of their own force (rows: x or uv), at the requested steps
//   solver.csv      step,relative_residual          ||A v1 - b|| / ||b|| of each step's solve
// Usage: published_driver OUT_DIR SIZE STEPS HEIGHT_M DUMP_STEPS(comma separated) [STEP_S [SOLVER]]
//   STEP_S  their h in seconds (default 0.001, their example's)
//   SOLVER  cg (default): their EigenSolver, conjugate gradients on the non-symmetric step matrix;
//           direct: the same system (their A and b) solved by a sparse LU of this driver's, so that
//           the step is their linearized implicit Euler without the residual CG leaves
#include <Eigen/SparseLU>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "PhysicsCloth.h"

namespace {

struct Options {
  std::string out_dir;
  int size = 17;
  int steps = 100;
  double height_m = 5.0;
  std::set<int> dump_steps;
  double step_s = 0.001;
  bool direct_solve = false;
};

[[noreturn]] void usage_error(const std::string& message) {
  std::cerr << "published_driver: " << message
            << "\nusage: published_driver OUT_DIR SIZE STEPS HEIGHT_M DUMP_STEPS [STEP_S [cg|direct]]\n";
  std::exit(2);
}

Options parse_options(int argc, char** argv) {
  if (argc < 6 || argc > 8) usage_error("expected 5 to 7 arguments");
  Options o;
  o.out_dir = argv[1];
  o.size = std::stoi(argv[2]);
  o.steps = std::stoi(argv[3]);
  o.height_m = std::stod(argv[4]);
  std::stringstream list(argv[5]);
  for (std::string item; std::getline(list, item, ',');)
    if (!item.empty()) o.dump_steps.insert(std::stoi(item));
  if (argc > 6) o.step_s = std::stod(argv[6]);
  if (!(o.step_s > 0.0)) usage_error(std::string("STEP_S ") + argv[6] + ": expected a positive step in seconds");
  if (argc > 7) {
    const std::string solver = argv[7];
    if (solver != "cg" && solver != "direct") usage_error("SOLVER " + solver + ": expected cg or direct");
    o.direct_solve = solver == "direct";
  }
  return o;
}

double value(const Tensor& t, int row) { return t.reshape({-1})[row].item<double>(); }

void write_state(std::ofstream& out, Cloth& cloth, int step, double time_s) {
  for (int j = 0; j < cloth.length; ++j)
    for (int i = 0; i < cloth.width; ++i) {
      const Node& n = cloth.nodes[std::to_string(i) + "," + std::to_string(j)];
      out << step << ',' << time_s << ',' << i << ',' << j;
      for (int k = 0; k < 3; ++k) out << ',' << value(n.LPos, k);
      if (n.is_edge) out << ",,";
      else out << ',' << value(n.EPos, 0) << ',' << value(n.EPos, 1);
      for (int k = 0; k < 3; ++k) out << ',' << value(n.LVel, k);
      if (n.is_edge) {
        out << ",,,,\n";
        continue;
      }
      out << ',' << value(n.EVel, 0) << ',' << value(n.EVel, 1) << ',' << value(n.EPosBar, 0) << ','
          << value(n.EPosBar, 1) << '\n';
    }
}

// One term's node-wise force arrays, written as rows of forces.csv.
void write_term(std::ofstream& out, const Cloth& cloth, int step, const std::string& term, const Tensor& f_l,
                const Tensor& f_e) {
  for (int j = 0; j < cloth.length; ++j)
    for (int i = 0; i < cloth.width; ++i) {
      const Tensor fl = f_l[i + j * cloth.width].reshape({-1});
      out << step << ',' << term << ',' << i << ',' << j << ',' << fl[0].item<double>() << ',' << fl[1].item<double>()
          << ',' << fl[2].item<double>() << ',';
      const bool interior = i > 0 && j > 0 && i < cloth.width - 1 && j < cloth.length - 1;
      if (!interior) {
        out << ",\n";
        continue;
      }
      const Tensor fe = f_e[(i - 1) + (j - 1) * (cloth.width - 2)].reshape({-1});
      out << fe[0].item<double>() << ',' << fe[1].item<double>() << '\n';
    }
}

// Evaluates each force routine of the published code on its own, into fresh arrays. Must run
// after FillMV (which sets the normal force read by shear); friction is the total minus the rest.
void write_forces(std::ofstream& out, PhysicsCloth& phy, Cloth& cloth, int step) {
  const auto zeros_l = [&] { return torch::zeros({cloth.num_nodes, 3, 1}, opts); };
  const auto zeros_e = [&] { return torch::zeros({cloth.num_cros_nodes, 2, 1}, opts); };
  Tensor sum_l = zeros_l(), sum_e = zeros_e();
  const auto emit = [&](const std::string& name, const Tensor& fl, const Tensor& fe) {
    write_term(out, cloth, step, name, fl, fe);
    sum_l = sum_l + fl;
    sum_e = sum_e + fe;
  };
  Tensor scratch_a = zeros_l(), scratch_b = zeros_l();
  Tensor fl = zeros_l(), fe = zeros_e();
  for (const Edge& e : cloth.edges) phy.Gravity_F(e, fl, fe);
  emit("gravity", fl, fe);
  fl = zeros_l(), fe = zeros_e();
  for (const Edge& e : cloth.edges) phy.Stretch_F(e, fl, fe, scratch_a, scratch_b);
  emit("stretch", fl, fe);
  fl = zeros_l(), fe = zeros_e();
  for (const Bend_Seg& b : cloth.bend_segs) phy.Bending_F(b, fl, fe, scratch_a);
  emit("bending", fl, fe);
  fl = zeros_l(), fe = zeros_e();
  for (const Edge& e : cloth.edges) phy.Inertia_F(e, fl, fe);
  emit("inertia_dT_dq", fl, fe);
  fl = zeros_l(), fe = zeros_e();
  for (const Edge& e : cloth.edges) phy.MDotVDot_F(e, fl, fe);
  emit("inertia_mdot_qdot", fl, fe);
  fl = zeros_l(), fe = zeros_e();
  for (const Edge& e : cloth.edges) phy.ParaColli_F(e, fe);
  emit("parallel_contact", fl, fe);
  fl = zeros_l(), fe = zeros_e();
  for (const Shear_Seg& s : cloth.shear_segs) phy.Shear_F(s, fl);
  emit("shear", fl, fe);
  fl = zeros_l(), fe = zeros_e();
  for (const Face& f : cloth.faces) phy.Wind_F(f, fl);
  emit("wind", fl, fe);
  fl = zeros_l(), fe = zeros_e();
  for (int i = 0; i < cloth.width; ++i)
    for (int j = 0; j < cloth.length; ++j) phy.Constraint_F(i, j, fl);
  emit("handles", fl, fe);
  write_term(out, cloth, step, "friction", phy.F_Ls[0] - sum_l, phy.F_Es[0] - sum_e);
  write_term(out, cloth, step, "total", phy.F_Ls[0], phy.F_Es[0]);
  // The contact normal force F_n of each interior crossing, in the fx column.
  Tensor fn = zeros_l();
  for (int j = 1; j < cloth.length - 1; ++j)
    for (int i = 1; i < cloth.width - 1; ++i)
      fn[i + j * cloth.width][0][0] = cloth.nodes[std::to_string(i) + "," + std::to_string(j)].comp.reshape({-1})[0];
  write_term(out, cloth, step, "normal_force", fn, zeros_e());
}

// Their force vector (get_SpaF) at a state; leaves the model filled at that state.
Tensor force_at(PhysicsCloth& phy, Cloth& cloth, const ClothState& state) {
  cloth.set_ClothState(state);
  phy.ResetMV();
  phy.FillMV();
  return phy.get_SpaF().clone();
}

ClothState copy_state(const ClothState& s) {
  return {s.LPos.clone(), s.LPosFix.clone(), s.LVel.clone(), s.EPos.clone(), s.EPosBar.clone(), s.EVel.clone()};
}

// Checks their assembled Jacobians against central differences of their force along a random
// direction of one block of DoFs, then restores the state (and the filled model) as it was.
void write_jacobian_checks(std::ofstream& out, PhysicsCloth& phy, Cloth& cloth, int step) {
  const Tensor K = phy.get_SpaFPos().clone(), D = phy.get_SpaFVel().clone();
  const ClothState base = copy_state(cloth.get_ClothState());
  const int n_l = 3 * cloth.num_nodes, n_all = n_l + 2 * cloth.num_cros_nodes;
  torch::manual_seed(step + 1);
  for (const std::string wrt : {"x", "uv", "vx", "vuv"}) {
    const bool on_position = wrt == "x" || wrt == "uv", on_uv = wrt == "uv" || wrt == "vuv";
    const double eps = on_position ? 1e-7 : 1e-6;
    ClothState plus = copy_state(base), minus = copy_state(base);
    Tensor direction = torch::zeros({n_all, 1}, opts);
    for (int j = 0; j < cloth.length; ++j)
      for (int i = 0; i < cloth.width; ++i) {
        const int node = i + j * cloth.width;
        const bool interior = i > 0 && j > 0 && i < cloth.width - 1 && j < cloth.length - 1;
        if (on_uv && !interior) continue;
        const Tensor d = torch::rand({on_uv ? 2 : 3, 1}, opts) - 0.5;
        const int row = on_uv ? n_l + 2 * ((i - 1) + (j - 1) * (cloth.width - 2)) : 3 * node;
        direction.slice(0, row, row + d.size(0)) = d;
        Tensor& p = on_position ? (on_uv ? plus.EPos : plus.LPos) : (on_uv ? plus.EVel : plus.LVel);
        Tensor& m = on_position ? (on_uv ? minus.EPos : minus.LPos) : (on_uv ? minus.EVel : minus.LVel);
        p[node] = p[node] + eps * d;
        m[node] = m[node] - eps * d;
      }
    const Tensor fd = (force_at(phy, cloth, plus) - force_at(phy, cloth, minus)) / (2.0 * eps);
    const Tensor analytic = torch::mm(on_position ? K : D, direction);
    for (const std::string rows : {"x", "uv"}) {
      const Tensor a = rows == "x" ? analytic.slice(0, 0, n_l) : analytic.slice(0, n_l, n_all);
      const Tensor f = rows == "x" ? fd.slice(0, 0, n_l) : fd.slice(0, n_l, n_all);
      out << step << ',' << wrt << ',' << rows << ',' << (torch::norm(a - f) / torch::norm(f)).item<double>() << ','
          << torch::norm(f).item<double>() << '\n';
    }
  }
  force_at(phy, cloth, base);
}

// Their step system A v1 = b solved by a sparse LU (A is their dense step matrix, not symmetric).
Tensor direct_solve(const Tensor& A, const Tensor& b) {
  const Tensor a = A.contiguous();
  const auto a_acc = a.accessor<double, 2>();
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < a.size(0); ++i)
    for (int j = 0; j < a.size(1); ++j)
      if (a_acc[i][j] != 0.0) entries.emplace_back(i, j, a_acc[i][j]);
  Eigen::SparseMatrix<double> sparse(a.size(0), a.size(1));
  sparse.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(sparse);
  if (lu.info() != Eigen::Success) {
    std::cerr << "published_driver: the step matrix is singular (sparse LU failed)\n";
    std::exit(1);
  }
  const Tensor rhs = b.contiguous();
  Tensor x = torch::zeros_like(rhs);
  Eigen::Map<Eigen::VectorXd>(x.data_ptr<double>(), x.numel()) =
      lu.solve(Eigen::Map<const Eigen::VectorXd>(rhs.data_ptr<double>(), rhs.numel()));
  return x;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse_options(argc, argv);
  // The parameters of the authors' homogeneous example, with Yarn1 everywhere (Gong et al. 2022 T1).
  const double L = 0.001, R = 0.0005;
  Tensor G = torch::tensor({0.0, 0.0, 9.8}, opts).view({3, 1});
  Yarn yarn{R, torch::tensor({0.002}, opts), torch::tensor({500000.0}, opts), torch::tensor({0.00014}, opts)};
  Wind wind{torch::tensor({0.0, 5.0, 0.0}, opts).view({3, 1}), torch::tensor({2.0}, opts), torch::tensor({0.5}, opts)};
  Cloth cloth(o.size, o.size, o.height_m, L, R, std::vector<Yarn>{yarn}, torch::tensor({1.0}, opts),
              torch::tensor({1000.0}, opts), torch::tensor({1000.0}, opts), torch::tensor({0.5}, opts),
              torch::tensor({1000.0}, opts), torch::tensor({1e4}, opts), WovenPattern::Plain, InitPose::Upright);
  Environment env{&cloth, G, wind};
  PhysicsCloth phy{&env};
  phy.InitMV();
  cloth.set_handles({{0, 0}, {o.size - 1, 0}});
  const Tensor h = torch::tensor({o.step_s}, opts);

  std::ofstream traj(o.out_dir + "/trajectory.csv"), forces(o.out_dir + "/forces.csv"),
      solver(o.out_dir + "/solver.csv"), jacobians(o.out_dir + "/jacobians.csv");
  jacobians << std::setprecision(17) << "step,wrt,rows,relative_error,fd_norm\n";
  traj << std::setprecision(17) << "step,time_s,i,j,x,y,z,u,v,vx,vy,vz,udot,vdot,u_anchor,v_anchor\n";
  forces << std::setprecision(17) << "step,term,i,j,fx,fy,fz,fu,fv\n";
  solver << std::setprecision(17) << "step,relative_residual\n";
  for (int step = 0; step < o.steps; ++step) {
    write_state(traj, cloth, step, step * o.step_s);
    phy.FillMV();
    if (o.dump_steps.count(step)) {
      write_forces(forces, phy, cloth, step);
      write_jacobian_checks(jacobians, phy, cloth, step);
    }
    // Their step, as in their simulation loop: (M - h^2 dF/dx - h dF/dv) v1 = h (F - dF/dv^T v0) + M v0.
    const Tensor A{phy.get_SpaM() - phy.get_SpaFPos() * torch::pow(h, 2) - phy.get_SpaFVel() * h};
    const Tensor b{h * (phy.get_SpaF() - torch::mm(phy.get_SpaFVel().transpose(0, 1), phy.get_SpaVel())) +
                   torch::mm(phy.get_SpaM(), phy.get_SpaVel())};
    Tensor new_vel = o.direct_solve ? direct_solve(A, b) : EigenSolver::apply(A, b);
    solver << step << ',' << (torch::norm(torch::mm(A, new_vel) - b) / torch::norm(b)).item<double>() << '\n';
    cloth.update(new_vel, phy.F_E_is_Slides[0], h);
    phy.ResetMV();
    std::cout << "step " << step + 1 << '/' << o.steps << std::endl;
  }
  write_state(traj, cloth, o.steps, o.steps * o.step_s);
  return 0;
}
