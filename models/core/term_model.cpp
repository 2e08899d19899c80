#include "models/core/term_model.h"

#include <algorithm>

namespace wl {
namespace {

// Sizes the force and makes the matrices `flags` asks for (kDfdq, kDfdv,
// kMass) pattern-shaped, leaving the others as they are (an evaluation that
// never asks for a matrix holds none) and the values already in place.
void shape_evaluation(const Model& model, unsigned flags, Evaluation& out) {
  const SparseMatrix& p = model.pattern();
  if (out.force.size() != model.num_dofs()) out.force = Vec::Zero(model.num_dofs());
  auto shape = [&](unsigned bit, SparseMatrix& m) {
    if ((flags & bit) && (m.rows() != p.rows() || m.nonZeros() != p.nonZeros())) m = p;
  };
  shape(kDfdq, out.dfdq);
  shape(kDfdv, out.dfdv);
  shape(kMass, out.mass);
}

}  // namespace

void allocate_evaluation(const Model& model, Evaluation& out) {
  out.force = Vec::Zero(model.num_dofs());
  out.dfdq = model.pattern();
  out.dfdv = model.pattern();
  out.mass = model.pattern();
}

void Model::evaluate_step(double t, const Vec& q, const Vec& v, const StepWeights& w, Evaluation& scratch,
                          SparseMatrix& a, Vec& r) {
  const unsigned flags = kForce | kDfdq | kStepStiffness | kDfdv | (w.constant_mass ? 0u : kMass);
  shape_evaluation(*this, flags, scratch);
  evaluate(t, q, v, flags, scratch);
  form_step(scratch, w, a, &r);
}

void form_step(const Evaluation& ev, const StepWeights& w, SparseMatrix& a, Vec* r) {
  const Eigen::Index nnz = a.nonZeros();
  const double* m = (w.constant_mass ? *w.constant_mass : ev.mass).valuePtr();
  const double* k = ev.dfdq.valuePtr();
  const double* d = ev.dfdv.valuePtr();
  double* av = a.valuePtr();
  for (Eigen::Index i = 0; i < nnz; ++i) av[i] = w.mass * m[i] + w.dfdv * d[i] + w.dfdq * k[i];
  if (!r) return;
  if (w.rhs_dfdq == 0.0) {
    *r = ev.force;
    return;
  }
  r->noalias() = ev.dfdq * *w.w;
  *r = ev.force + w.rhs_dfdq * *r;
}

double Model::kinetic_energy(double t, const Vec& q, const Vec& v, Evaluation& scratch) {
  shape_evaluation(*this, kMass, scratch);
  evaluate(t, q, v, kMass, scratch);
  return 0.5 * v.dot(scratch.mass * v);
}

TermModel::TermModel(const TermModel& other)
    : Model(other),
      num_dofs_(other.num_dofs_),
      q0_(other.q0_),
      v0_(other.v0_),
      constants_(other.constants_),
      fixed_(other.fixed_),
      extra_pattern_(other.extra_pattern_) {
  for (const auto& t : other.terms_) terms_.push_back(t->clone());
  finalize();
}

void TermModel::finalize() {
  std::vector<Term*> raw;
  for (auto& t : terms_) raw.push_back(t.get());
  assembly_ = std::make_unique<Assembly>(num_dofs_, raw, extra_pattern_);
  std::sort(fixed_.begin(), fixed_.end());
  fixed_.erase(std::unique(fixed_.begin(), fixed_.end()), fixed_.end());
}

void TermModel::replace_terms(std::vector<std::unique_ptr<Term>> terms) {
  std::vector<Term*> raw;
  for (auto& t : terms) raw.push_back(t.get());
  assembly_->rebind(raw);
  terms_ = std::move(terms);
}

void TermModel::evaluate(double t, const Vec& q, const Vec& v, unsigned flags, Evaluation& out) {
  shape_evaluation(*this, flags, out);
  out.force.setZero();
  AssemblyRequest req{(flags & kDfdq) != 0, (flags & kDfdv) != 0, (flags & kMass) != 0};
  req.step_stiffness = (flags & kStepStiffness) != 0;
  if (flags & kExplicitTerms) req.filter = TermFilter::explicit_only;
  else if (flags & kImplicitTerms) req.filter = TermFilter::implicit_only;
  else if (flags == kMass) req.filter = TermFilter::mass_only;
  auto zero = [](SparseMatrix& m) { std::fill(m.valuePtr(), m.valuePtr() + m.nonZeros(), 0.0); };
  if (req.dfdq) zero(out.dfdq);
  if (req.dfdv) zero(out.dfdv);
  if (req.mass) zero(out.mass);

  if (req.filter == TermFilter::mass_only) {  // M(q) alone: no auxiliaries, only the mass terms (stage 0)
    assembly_->add_stage(0, q, v, constants_, req, out.force, nullptr, nullptr, &out.mass);
    return;
  }
  assemble_stages(t, q, v, req, out, &out.dfdq, &out.dfdv, &out.mass);
}

void TermModel::assemble_stages(double t, const Vec& q, const Vec& v, const AssemblyRequest& req, Evaluation& out,
                                SparseMatrix* dfdq, SparseMatrix* dfdv, SparseMatrix* mass) {
  EvalContext ctx{t, &q, &v, nullptr};
  prepare_auxiliary(t, q, v, ctx);
  bool has_stage1 = false;
  for (auto& term : terms_) {
    if (term->stage() == 0) term->prepare(ctx);
    else has_stage1 = true;
  }
  assembly_->add_stage(0, q, v, constants_, req, out.force, dfdq, dfdv, mass);
  if (!req.step) after_stage(0, q, v, req, out);
  if (has_stage1) {
    stage0_force_ = out.force;
    ctx.force_so_far = &stage0_force_;
    for (auto& term : terms_)
      if (term->stage() == 1) term->prepare(ctx);
    assembly_->add_stage(1, q, v, constants_, req, out.force, dfdq, dfdv, mass);
  }
  if (!req.step) after_stage(1, q, v, req, out);
}

// One pass (docs/design.md §3.3) unless the model adds derivatives of its
// auxiliaries after a stage (single_pass_step() false): those need ∂f/∂q and
// ∂f/∂v apart.
void TermModel::evaluate_step(double t, const Vec& q, const Vec& v, const StepWeights& w, Evaluation& scratch,
                              SparseMatrix& a, Vec& r) {
  if (!single_pass_step()) {
    Model::evaluate_step(t, q, v, w, scratch, a, r);
    return;
  }
  shape_evaluation(*this, kForce, scratch);  // the matrices are not used: A is formed in `a`
  scratch.force.setZero();
  r.setZero(num_dofs_);  // (∂f/∂q)·w first
  double* av = a.valuePtr();
  const Eigen::Index nnz = a.nonZeros();
  if (w.constant_mass) {
    const double* m = w.constant_mass->valuePtr();
    for (Eigen::Index k = 0; k < nnz; ++k) av[k] = w.mass * m[k];
  } else {
    std::fill(av, av + nnz, 0.0);
  }
  AssemblyRequest req;
  req.step = &w;
  req.dfdq_w = &r;
  assemble_stages(t, q, v, req, scratch, &a, nullptr, nullptr);
  r = scratch.force + w.rhs_dfdq * r;
}

void TermModel::gather_local(const Term& term, int e, const Vec& q, const Vec& v, double* lq, double* lv) const {
  const auto s = term.stencil(e);
  for (size_t a = 0; a < s.size(); ++a) {
    lq[a] = is_dof(s[a]) ? q[s[a]] : constants_[constant_slot(s[a])];
    lv[a] = is_dof(s[a]) ? v[s[a]] : 0.0;
  }
}

std::vector<TermModel::TermReading> TermModel::term_readings(double t, const Vec& q, const Vec& v, bool prepare) {
  Evaluation scratch;
  if (prepare) evaluate(t, q, v, kForce, scratch);  // prepares every term at (t, q, v)
  std::vector<double> energy, power;
  assembly_->term_energies_and_powers(q, v, constants_, energy, power);
  std::vector<TermReading> out;
  for (size_t k = 0; k < terms_.size(); ++k) {
    auto it = std::find_if(out.begin(), out.end(), [&](const TermReading& r) { return r.name == terms_[k]->name(); });
    if (it == out.end()) it = out.insert(out.end(), TermReading{terms_[k]->name()});
    it->energy_J += energy[k];
    it->power_W += power[k];
    it->mass = it->mass || terms_[k]->provides_mass();
    it->conservative = it->conservative && terms_[k]->conservative() && !it->mass;
  }
  return out;
}

double TermModel::potential_energy(const Vec& q) const { return assembly_->energy(q, constants_); }

double TermModel::kinetic_energy(double, const Vec& q, const Vec& v, Evaluation&) {
  return assembly_->kinetic_energy(q, v, constants_);
}

void TermModel::accept_step(double t, const Vec& q, const Vec& v, double h) {
  EvalContext ctx{t, &q, &v, nullptr};
  for (auto& term : terms_) term->accept_step(ctx, h);
}

bool TermModel::projects_step_stiffness() const {
  return std::any_of(terms_.begin(), terms_.end(), [](const auto& t) { return t->projects_step_stiffness(); });
}

bool TermModel::constrains_steps() const {
  return std::any_of(terms_.begin(), terms_.end(), [](const auto& t) { return t->constrains_steps(); });
}

double TermModel::admissible_fraction(double t0, const Vec& q0, double t1, const Vec& q1) const {
  const EvalContext from{t0, &q0, nullptr, nullptr}, to{t1, &q1, nullptr, nullptr};
  double alpha = 1.0;
  for (const auto& term : terms_)
    if (term->constrains_steps()) alpha = std::min(alpha, term->admissible_fraction(from, to));
  return alpha;
}

std::vector<std::string> TermModel::parameter_keys() const {
  std::vector<std::string> keys;
  for (const auto& term : terms_)
    for (const std::string& k : term->parameter_keys())
      if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
  return keys;
}

std::string TermModel::term_counts() const {
  std::string out;
  for (const auto& t : terms_)
    out += (out.empty() ? "" : ", ") + t->name() + " (" + std::to_string(t->num_elements()) + ")";
  return out;
}

std::vector<std::string> TermModel::asymmetric_terms() const {
  std::vector<std::string> names;
  for (const auto& term : terms_)
    if (!term->symmetric_jacobian() && std::find(names.begin(), names.end(), term->name()) == names.end())
      names.push_back(term->name());
  return names;
}

bool TermModel::force_parameter_derivative(const std::string& key, double, const Vec& q, const Vec& v,
                                           Vec& dfdp) const {
  dfdp = Vec::Zero(num_dofs_);
  return assembly_->add_parameter_derivative(key, q, v, constants_, dfdp);
}

void TermModel::mass_directional_product(const Vec& q, const Vec& dq, const Vec& w, Vec& out) const {
  if (mass_depends_on_q()) assembly_->add_mass_directional_product(q, dq, w, constants_, out);
}

bool TermModel::mass_parameter_product(const std::string& key, const Vec& q, const Vec& w, Vec& out) const {
  return assembly_->add_mass_parameter_product(key, q, w, constants_, out);
}

}  // namespace wl
