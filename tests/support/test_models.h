// Small models for the integrator tests, built from Terms like the real models.
//  - SpringChain: a 1-D linear mass–spring chain; DoF 0 is pinned at 0, DoFs
//    1..N carry mass m, springs k with rest length L between neighbours and a
//    constant force m·g on every free mass (an IMEX-explicit term, like
//    gravity). Linear, so it has a closed-form solution (exact_state).
//  - VariableMassOscillator: one DoF with mass m(q) = m0 (1 + α q²) and a
//    spring k: Lagrangian EOM m(q) q̈ = −k q − ½ m′(q) q̇² (docs/models.md §3.1.2: f
//    includes ∂T/∂q − Ṁq̇). Energy ½ m(q) q̇² + ½ k q² is conserved.
//  - SpringNet: a 3-D nonlinear spring net on an r×c grid (structural and
//    diagonal springs, rest length = initial length), gravity, two corners
//    pinned; the mid-size problem for linear-solver timings.
#pragma once
#include <memory>

#include "models/core/term_model.h"

namespace wl::test {

class SpringChain : public TermModel {
 public:
  SpringChain(int num_masses, double m, double k, double rest_length, double g);
  std::unique_ptr<Model> clone() const override { return std::make_unique<SpringChain>(*this); }
  std::string name() const override { return "spring-chain"; }
  bool mass_depends_on_q() const override { return false; }
  Frame frame(double t, const Vec& q, const Vec& v) const override;
  std::map<std::string, std::string> describe() const override { return {}; }
  void set_initial(const Vec& q0, const Vec& v0) {
    q0_ = q0;
    v0_ = v0;
  }
  // Closed-form state at time t from (q0, v0) at 0, by eigen-decomposition of
  // the free block (q0[0] must be 0, the pinned position).
  void exact_state(double t, Vec& q, Vec& v) const;
  double total_energy(const Vec& q, const Vec& v) const;
  // Energy of the static equilibrium (the minimum of total_energy).
  double equilibrium_energy() const;
  // Largest angular frequency of the chain [rad/s].
  double max_frequency() const;

 private:
  int n_;
  double m_, k_, l_, g_;
};

class VariableMassOscillator : public TermModel {
 public:
  VariableMassOscillator(double m0, double alpha, double k, double q0, double v0);
  std::unique_ptr<Model> clone() const override { return std::make_unique<VariableMassOscillator>(*this); }
  std::string name() const override { return "variable-mass-oscillator"; }
  bool mass_depends_on_q() const override { return true; }
  Frame frame(double t, const Vec& q, const Vec& v) const override;
  std::map<std::string, std::string> describe() const override { return {}; }
  double total_energy(const Vec& q, const Vec& v) const;

 private:
  double m0_, alpha_, k_;
};

class SpringNet : public TermModel {
 public:
  SpringNet(int rows, int cols, double spacing, double mass_per_node, double k, double damping);
  std::unique_ptr<Model> clone() const override { return std::make_unique<SpringNet>(*this); }
  std::string name() const override { return "spring-net"; }
  bool mass_depends_on_q() const override { return false; }
  Frame frame(double t, const Vec& q, const Vec& v) const override;
  std::map<std::string, std::string> describe() const override { return {}; }
};

// Terms, exposed for the finite-difference checks.
std::unique_ptr<Term> make_linear_spring_1d(std::vector<std::array<int, 2>> stencils, double k, double rest_length);
std::unique_ptr<Term> make_spring_3d(std::vector<std::array<int, 6>> stencils, std::vector<double> rest_lengths,
                                     double k, double damping);
std::unique_ptr<Term> make_variable_mass_term(double m0, double alpha);

}  // namespace wl::test
