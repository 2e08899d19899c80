#include "models/scene/mixed_reader.h"

#include <string>

namespace wl::scene_detail {
namespace {

// One rectangle [i0, j0, i1, j1] of crossings inside the grid, i0 ≤ i1 and j0 ≤ j1.
std::array<int, 4> read_rectangle(TableReader& m, const toml::node& n, const std::string& key, const Scene& s,
                                  const std::string& expected) {
  const auto* a = n.as_array();
  if (!a || a->size() != 4) m.fail_at(n, key, expected);
  std::array<int, 4> r{};
  for (int k = 0; k < 4; ++k) {
    const auto* x = a->get(k)->as_integer();
    if (!x) m.fail_at(n, key, expected);
    const long long limit = k % 2 == 0 ? s.wefts : s.warps;
    if (x->get() < 0 || x->get() >= limit) m.fail_at(n, key, expected);
    r[k] = static_cast<int>(x->get());
  }
  if (r[0] > r[2] || r[1] > r[3]) m.fail_at(n, key, expected);
  return r;
}

}  // namespace

void read_mixed(TableReader& top, Scene& s) {
  auto m = top.subtable("mixed");
  if (!m) return;
  if (s.knit)
    top.source().fail(m->line(), "mixed", "[mixed]",
                      "no [mixed] table in a knit scene (the mixed model couples the woven yarn level)");
  MixedSettings& mixed = s.mixed;
  mixed.present = true;
  mixed.line = m->line();
  const std::string expected =
      "an array of rectangles [i0, j0, i1, j1] of crossings, integers with 0 ≤ i0 ≤ i1 < "
      "cloth.wefts (= " +
      std::to_string(s.wefts) + ") and 0 ≤ j0 ≤ j1 < cloth.warps (= " + std::to_string(s.warps) + "); [] for none";
  const toml::node* n = m->get("yarn_region");
  if (!n) m->fail_missing("yarn_region", expected);
  const auto* rectangles = n->as_array();
  if (!rectangles) m->fail_at(*n, "yarn_region", expected);
  for (size_t k = 0; k < rectangles->size(); ++k)
    mixed.yarn_region.push_back(
        read_rectangle(*m, *rectangles->get(k), "yarn_region[" + std::to_string(k) + "]", s, expected));
  m->finish();
}

}  // namespace wl::scene_detail
