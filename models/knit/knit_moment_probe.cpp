#include "models/knit/knit_moment_probe.h"

#include <algorithm>
#include <vector>

#include "models/knit/knit_model.h"

namespace wl {

std::map<std::string, double> course_cut_moment(const KnitModel& model, const Vec& q, const CourseCut& cut) {
  // The node and the component of every position DoF (−1: a coordinate).
  std::vector<int> node_of(q.size(), -1), component(q.size(), -1);
  for (int k = 0; k < model.graph().num_nodes(); ++k)
    for (int d = 0; d < 3; ++d) {
      node_of[model.graph().node(k).x_dof + d] = k;
      component[model.graph().node(k).x_dof + d] = d;
    }
  std::map<std::string, double> moment;
  const Vec v = Vec::Zero(q.size());
  for (const auto& term : model.terms()) {
    const int n = term->stencil_size();
    std::vector<double> lq(n), lv(n), f(n);
    double& sum = moment[term->name()];
    for (int e = 0; e < term->num_elements(); ++e) {
      const auto st = term->stencil(e);
      model.gather_local(*term, e, q, v, lq.data(), lv.data());
      // Each node's position, from the local state.
      std::map<int, Vec3> x;
      for (int a = 0; a < n; ++a)
        if (st[a] >= 0 && node_of[st[a]] >= 0)
          x.emplace(node_of[st[a]], Vec3::Zero()).first->second[component[st[a]]] = lq[a];
      bool below = false, above = false;
      Vec3 mean = Vec3::Zero();
      for (const auto& [k, p] : x) {
        (p.y() > cut.y ? above : below) = true;
        mean += p / static_cast<double>(x.size());
      }
      if (!(below && above) || mean.x() < cut.x_min || mean.x() >= cut.x_max) continue;
      std::fill(f.begin(), f.end(), 0.0);
      term->evaluate(e, lq.data(), lv.data(), ElementOutput{f.data()});
      for (int a = 0; a < n; ++a) {
        if (st[a] < 0 || node_of[st[a]] < 0) continue;
        const Vec3& p = x[node_of[st[a]]];
        if (!(p.y() > cut.y)) continue;
        if (component[st[a]] == 2) sum += (p.y() - cut.y) * f[a];
        if (component[st[a]] == 1) sum -= (p.z() - cut.z_ref) * f[a];
      }
    }
  }
  return moment;
}

}  // namespace wl
