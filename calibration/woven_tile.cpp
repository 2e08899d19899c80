#include "calibration/woven_tile.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <span>
#include <stdexcept>
#include <unsupported/Eigen/AutoDiff>

#include "models/knit/image_term.h"
#include "models/yarn/contact_normals.h"
#include "models/yarn/terms/bending.h"
#include "models/yarn/terms/shear_cirio.h"
#include "models/yarn/terms/shear_gong.h"
#include "models/yarn/terms/stretch.h"
#include "models/yarn/woven_grid.h"

namespace wl {
namespace {

using StrainAD = Eigen::AutoDiffScalar<Eigen::Matrix<double, 6, 1>>;

// φ(X) of the header in any scalar type (double or the six-strain AD scalar).
template <class T>
Eigen::Matrix<T, 3, 1> map_of(const std::array<T, 6>& th, const Vec2& X) {
  using std::cos;
  using std::sin;
  const T c = cos(0.5 * th[2]), s = sin(0.5 * th[2]);
  Eigen::Matrix<T, 3, 2> A;
  A << (1.0 + th[0]) * c, (1.0 + th[1]) * s, (1.0 + th[0]) * s, (1.0 + th[1]) * c, T(0.0), T(0.0);
  Eigen::Matrix<T, 2, 2> B;
  B << th[3], th[5], th[5], th[4];
  const Eigen::Matrix<T, 2, 1> Xt(T(X.x()), T(X.y()));
  const Eigen::Matrix<T, 2, 1> BX = B * Xt;
  const T sX = Xt.dot(BX);
  const Eigen::Matrix<T, 2, 2> G = A.transpose() * A;
  const T det = G(0, 0) * G(1, 1) - G(0, 1) * G(1, 0);
  const Eigen::Matrix<T, 2, 1> GinvBX((G(1, 1) * BX[0] - G(0, 1) * BX[1]) / det,
                                      (G(0, 0) * BX[1] - G(1, 0) * BX[0]) / det);
  Eigen::Matrix<T, 3, 1> x = A * Xt - (1.0 / 6.0) * (A * GinvBX) * sX;
  x[2] += 0.5 * sX;
  return x;
}

int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// The smallest p > 0 with same(k + p) for every k of a long enough range.
template <class Same>
int period_of(Same same) {
  for (int p = 1; p <= 256; ++p) {
    bool ok = true;
    for (int k = 0; k < 512 && ok; ++k) ok = same(k, k + p);
    if (ok) return p;
  }
  throw std::invalid_argument("woven tile: the pattern repeats over no period up to 256 crossings");
}

template <size_t N>
std::array<int, N> as_stencil(const std::vector<int>& dofs) {
  std::array<int, N> s{};
  std::copy(dofs.begin(), dofs.end(), s.begin());
  return s;
}

}  // namespace

Vec3 macro_map(const MacroStrain& theta, const Vec2& X, StrainJacobian* dphi) {
  if (!dphi) return map_of<double>(theta, X);
  std::array<StrainAD, 6> th;
  for (int k = 0; k < 6; ++k) th[k] = StrainAD(theta[k], 6, k);
  const Eigen::Matrix<StrainAD, 3, 1> x = map_of<StrainAD>(th, X);
  Vec3 value;
  for (int r = 0; r < 3; ++r) {
    value[r] = x[r].value();
    dphi->row(r) = x[r].derivatives().transpose();
  }
  return value;
}

WovenTileSize woven_tile_size(const Scene& scene) {
  if (scene.knit) throw std::invalid_argument("woven tile: the scene is knitted (its tile is the knit's rest shape)");
  const Pattern& p = scene.pattern;
  const int along_i = period_of([&](int a, int b) {
    for (int j = 0; j < 64; ++j)
      if (pattern_sign(p, a, j) != pattern_sign(p, b, j)) return false;
    return true;
  });
  const int along_j = period_of([&](int a, int b) {
    for (int i = 0; i < 64; ++i)
      if (pattern_sign(p, i, a) != pattern_sign(p, i, b)) return false;
    return true;
  });
  // Weft i carries weft_yarn_types[i mod …], warp j warp_yarn_types[j mod …].
  const int weft_cycle = static_cast<int>(scene.weft_yarn_types.size());
  const int warp_cycle = static_cast<int>(scene.warp_yarn_types.size());
  return {std::lcm(along_i, weft_cycle), std::lcm(along_j, warp_cycle)};
}

void WovenTileModel::Entries::position(const WovenTileModel& tile, const Image& im) {
  const double L = tile.scene_.spacing_m;
  const Vec2 D(im.m * tile.size_.nu * L, im.n * tile.size_.nv * L);
  StrainJacobian d_image = StrainJacobian::Zero(), d_node = StrainJacobian::Zero();
  const Vec3 s = tile.rotation_ * (macro_map(tile.theta_, im.X, &d_image) - macro_map(tile.theta_, im.X - D, &d_node));
  const StrainJacobian ds = tile.rotation_ * (d_image - d_node);
  for (int r = 0; r < 3; ++r) {
    dofs.push_back(3 * im.node + r);
    const bool shifted = im.m != 0 || im.n != 0;
    shift.push_back(shifted ? s[r] : 0.0);
    for (int k = 0; k < 6; ++k) dshift.push_back(shifted ? ds(r, k) : 0.0);
  }
}

void WovenTileModel::Entries::coordinate(const WovenTileModel& tile, const Image& im, bool warp) {
  const double L = tile.scene_.spacing_m;
  dofs.push_back(encode_constant(2 * im.node + (warp ? 0 : 1)));
  shift.push_back(warp ? im.m * tile.size_.nu * L : im.n * tile.size_.nv * L);
  for (int k = 0; k < 6; ++k) dshift.push_back(0.0);
}

WovenTileModel::WovenTileModel(const Scene& scene, const MacroStrain& theta, const Mat3& rotation)
    : scene_(scene), size_(woven_tile_size(scene)), theta_(theta), rotation_(rotation) {
  set_state();
  if (scene_.terms.stretch) add_stretch();
  if (scene_.terms.bending) add_bending();
  if (scene_.terms.shear) add_shear();
  finalize();
}

WovenTileModel::Image WovenTileModel::image(int i, int j) const {
  const int m = floor_div(i, size_.nu), n = floor_div(j, size_.nv);
  const double L = scene_.spacing_m;
  const Vec2 X(i * L - 0.5 * (size_.nu - 1) * L, j * L - 0.5 * (size_.nv - 1) * L);
  return {(i - m * size_.nu) + size_.nu * (j - n * size_.nv), m, n, X};
}

// Nodes at Qφ(X) translated so that node 0 sits at its rest place (iL, jL, 0);
// u = iL, v = jL frozen.
void WovenTileModel::set_state() {
  const int nodes = size_.nu * size_.nv;
  const double L = scene_.spacing_m;
  num_dofs_ = 3 * nodes;
  q0_ = Vec::Zero(num_dofs_);
  v0_ = Vec::Zero(num_dofs_);
  constants_ = Vec::Zero(2 * nodes);
  const Vec3 translation = -rotation_ * macro_map(theta_, image(0, 0).X);
  for (int j = 0; j < size_.nv; ++j)
    for (int i = 0; i < size_.nu; ++i) {
      const Image im = image(i, j);
      q0_.segment<3>(3 * im.node) = rotation_ * macro_map(theta_, im.X) + translation;
      constants_[2 * im.node] = i * L;
      constants_[2 * im.node + 1] = j * L;
    }
  fixed_ = {0, 1, 2};
}

void WovenTileModel::add_term(std::unique_ptr<Term> term, const std::vector<Entries>& elements) {
  std::vector<double> shift, dshift;
  for (const Entries& e : elements) {
    shift.insert(shift.end(), e.shift.begin(), e.shift.end());
    dshift.insert(dshift.end(), e.dshift.begin(), e.dshift.end());
  }
  terms_.push_back(std::make_unique<ImageTerm>(std::move(term), std::move(shift)));
  dshift_.push_back(std::move(dshift));
}

// Stretch on every segment of every warp and weft through the tile (docs/models.md §3.2).
void WovenTileModel::add_stretch() {
  const double area = std::numbers::pi * scene_.radius_m * scene_.radius_m;
  auto term = std::make_unique<StretchTerm>();
  std::vector<Entries> elements;
  auto segment = [&](int i0, int j0, int i1, int j1, bool warp, double ks) {
    Entries e;
    e.position(*this, image(i0, j0));
    e.position(*this, image(i1, j1));
    e.coordinate(*this, image(i0, j0), warp);
    e.coordinate(*this, image(i1, j1), warp);
    term->add(as_stencil<8>(e.dofs), ks);
    elements.push_back(std::move(e));
  };
  for (int j = 0; j < size_.nv; ++j)
    for (int i = 0; i < size_.nu; ++i) {
      segment(i, j, i + 1, j, true, scene_.warp_type(j).stretch_modulus_Pa * area);
      segment(i, j, i, j + 1, false, scene_.weft_type(i).stretch_modulus_Pa * area);
    }
  add_term(std::move(term), elements);
}

// Bending over (centre, next, previous) of every warp and weft (docs/models.md §3.3).
void WovenTileModel::add_bending() {
  const double area = std::numbers::pi * scene_.radius_m * scene_.radius_m;
  auto term = std::make_unique<BendingTerm>();
  std::vector<Entries> elements;
  auto bend = [&](int i, int j, int di, int dj, bool warp, double kb) {
    Entries e;
    e.position(*this, image(i, j));
    e.position(*this, image(i + di, j + dj));
    e.position(*this, image(i - di, j - dj));
    e.coordinate(*this, image(i + di, j + dj), warp);
    e.coordinate(*this, image(i - di, j - dj), warp);
    const std::array<int, 11> st = as_stencil<11>(e.dofs);
    term->add(st, kb);
    elements.push_back(std::move(e));
  };
  for (int j = 0; j < size_.nv; ++j)
    for (int i = 0; i < size_.nu; ++i) {
      bend(i, j, 1, 0, true, scene_.warp_type(j).bending_modulus_Pa * area);
      bend(i, j, 0, 1, false, scene_.weft_type(i).bending_modulus_Pa * area);
    }
  add_term(std::move(term), elements);
}

// Shear on the four quadrants of every crossing (docs/models.md §3.4), Gong's
// with F_n frozen at the flat fabric's rest value, or Cirio's.
void WovenTileModel::add_shear() {
  const ContactParams& c = scene_.contact;
  const double L = scene_.spacing_m, area = std::numbers::pi * scene_.radius_m * scene_.radius_m;
  const bool gong_law = c.shear_model == ContactParams::ShearModel::gong;
  auto gong = std::make_unique<GongShearTerm>(L, scene_.radius_m, c.lock_exponent, c.lock_sigma);
  auto cirio = std::make_unique<CirioShearTerm>();
  std::vector<Entries> elements;
  auto sign = [&](int i, int j) { return pattern_sign(scene_.pattern, i, j); };
  for (int j = 0; j < size_.nv; ++j)
    for (int i = 0; i < size_.nu; ++i)
      for (int di : {1, -1})
        for (int dj : {1, -1}) {
          Entries e;
          e.position(*this, image(i, j));
          e.position(*this, image(i + di, j));
          e.position(*this, image(i, j + dj));
          const std::array<int, 9> st = as_stencil<9>(e.dofs);
          const bool lock = sign(i, j) != sign(i + di, j) && sign(i, j) != sign(i, j + dj);
          if (gong_law) gong->add(st, image(i, j).node, c.shear_modulus_Pa * area, lock);
          else cirio->add(st, c.shear_modulus_Pa * area * L);
          elements.push_back(std::move(e));
        }
  if (!gong_law) return add_term(std::move(cirio), elements);
  // The wrapper does not forward prepare(): F_n is frozen here, once.
  const std::vector<double> fn = rest_normal_force();
  EvalContext ctx;
  ctx.normal_force = std::span<const double>(fn);
  gong->prepare(ctx);
  add_term(std::move(gong), elements);
}

// F_n (docs/models.md §3.6) at the tile's crossings on the flat fabric at rest:
// read inside a flat patch of three tiles per direction, whose middle tile is
// two crossings or more from the patch's ring (F_n's stencil).
std::vector<double> WovenTileModel::rest_normal_force() const {
  const int ou = size_.nu * ((3 + size_.nu - 1) / size_.nu), ov = size_.nv * ((3 + size_.nv - 1) / size_.nv);
  Scene patch = scene_;
  patch.wefts = size_.nu + 2 * ou;
  patch.warps = size_.nv + 2 * ov;
  patch.sliding = false;
  const WovenGrid grid(patch);
  const double area = std::numbers::pi * scene_.radius_m * scene_.radius_m, L = scene_.spacing_m;
  std::vector<double> wks, wkb, fks, fkb;
  for (int j = 0; j < grid.nv(); ++j) {
    wks.push_back(patch.warp_type(j).stretch_modulus_Pa * area);
    wkb.push_back(patch.warp_type(j).bending_modulus_Pa * area);
  }
  for (int i = 0; i < grid.nu(); ++i) {
    fks.push_back(patch.weft_type(i).stretch_modulus_Pa * area);
    fkb.push_back(patch.weft_type(i).bending_modulus_Pa * area);
  }
  ContactNormals normals(grid, wks, wkb, fks, fkb, scene_.radius_m);
  Vec q = Vec::Zero(grid.num_dofs());
  for (int j = 0; j < grid.nv(); ++j)
    for (int i = 0; i < grid.nu(); ++i) q.segment<3>(grid.dofs(grid.node(i, j)).x) = Vec3(i * L, j * L, 0.0);
  normals.compute(q);
  std::vector<double> fn(size_.nu * size_.nv);
  for (int j = 0; j < size_.nv; ++j)
    for (int i = 0; i < size_.nu; ++i) fn[image(i, j).node] = normals.normal_force()[grid.node(ou + i, ov + j)];
  return fn;
}

double WovenTileModel::rest_area() const { return size_.nu * size_.nv * scene_.spacing_m * scene_.spacing_m; }

Eigen::Matrix<double, 1, 6> WovenTileModel::strain_partial(const Vec& q) const {
  Eigen::Matrix<double, 1, 6> dE = Eigen::Matrix<double, 1, 6>::Zero();
  const Vec v = Vec::Zero(num_dofs_);
  std::vector<double> lq, lv, f;
  for (size_t t = 0; t < terms_.size(); ++t) {
    const Term& term = *terms_[t];
    const int n = term.stencil_size();
    lq.assign(n, 0.0);
    lv.assign(n, 0.0);
    for (int e = 0; e < term.num_elements(); ++e) {
      gather_local(term, e, q, v, lq.data(), lv.data());
      f.assign(n, 0.0);
      term.evaluate(e, lq.data(), lv.data(), ElementOutput{f.data()});
      for (int a = 0; a < n; ++a)
        for (int k = 0; k < 6; ++k) dE[k] -= f[a] * dshift_[t][(static_cast<size_t>(e) * n + a) * 6 + k];
    }
  }
  return dE;
}

Frame WovenTileModel::frame(double t, const Vec& q, const Vec& v) const {
  Frame f;
  f.time = t;
  const int nodes = size_.nu * size_.nv;
  f.points.resize(nodes, 3);
  for (int k = 0; k < nodes; ++k) f.points.row(k) = q.segment<3>(3 * k).transpose();
  return f;
}

std::map<std::string, std::string> WovenTileModel::describe() const {
  return {{"tile", std::to_string(size_.nu) + " x " + std::to_string(size_.nv)}, {"terms", term_counts()}};
}

}  // namespace wl
