// Free nodes of mass m for contact tests: a constant mass block m I per node
// (nodes 0 … n−1 at DoFs 3k … 3k+2), no force.
#pragma once
#include <memory>
#include <string>

#include "models/core/term.h"
#include "models/core/term_model.h"

namespace wl::test {

class NodeMassTerm : public StencilTerm<3> {
 public:
  NodeMassTerm(int nodes, double m) : m_(m) {
    for (int k = 0; k < nodes; ++k) stencils_.push_back({3 * k, 3 * k + 1, 3 * k + 2});
  }
  std::string name() const override { return "node-mass"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<NodeMassTerm>(*this); }
  bool provides_mass() const override { return true; }
  double energy(int, const double*) const override { return 0.0; }
  void evaluate(int, const double*, const double*, const ElementOutput& out) const override {
    if (out.mass) MatMap(out.mass) = m_ * Mat3::Identity();
  }

 private:
  double m_;
};

// A model of hand-built terms with a constant mass (NodeMassTerm), no frame
// data and no description: `Derived` fills num_dofs_, q0_, v0_, terms_ (and
// fixed_) and calls finalize(); `name` names it.
template <class Derived>
class HandBuiltModel : public TermModel {
 public:
  explicit HandBuiltModel(std::string name) : name_(std::move(name)) {}
  std::unique_ptr<Model> clone() const override {
    return std::make_unique<Derived>(static_cast<const Derived&>(*this));
  }
  std::string name() const override { return name_; }
  bool mass_depends_on_q() const override { return false; }
  Frame frame(double t, const Vec&, const Vec&) const override {
    Frame f;
    f.time = t;
    return f;
  }
  std::map<std::string, std::string> describe() const override { return {}; }

 private:
  std::string name_;
};

}  // namespace wl::test
