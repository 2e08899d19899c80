// The moment across a course cut of the tiled rest shape, term by term
// (models/knit/knit_moment_probe.h, docs/models.md §11.3.2).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "models/knit/knit_model.h"
#include "models/knit/knit_moment_probe.h"
#include "models/knit/knit_rest_shape.h"

namespace wl {
namespace {

Scene moment_scene(const std::string& kind) {
  return parse_scene("[cloth]\nspacing_m = 0.002\nradius_m = 0.0002\nsliding = true\n[cloth.pattern]\nkind = \"" +
                         kind +
                         "\"\ncourses = 6\nwales = 8\ncourse_spacing_m = 0.0016\n"
                         "[pose]\nkind = \"flat\"\n[gravity]\nacceleration_m_per_s2 = [0, 0, 0]\n",
                     "knit_moment.toml");
}

// The cut y = (r + dy)·C·s₁ over the middle four wales (x from 1.5 to 5.5 W·s₀,
// the rest period's loop width), the moment's axis at height z_ref.
CourseCut course_cut(const Scene& s, double r, double z_ref) {
  const std::array<double, 2> p = relaxed_tile(s).period_scale;
  CourseCut cut;
  cut.y = r * s.knit->course_spacing_m * p[1];
  cut.z_ref = z_ref;
  cut.x_min = 1.5 * s.spacing_m * p[0];
  cut.x_max = 5.5 * s.spacing_m * p[0];
  return cut;
}

struct Moment {
  double total = 0.0, largest_part = 0.0;
};

Moment moment(const KnitModel& m, const CourseCut& cut) {
  Moment out;
  for (const auto& [name, value] : course_cut_moment(m, m.initial_q(), cut)) {
    out.total += value;
    out.largest_part = std::max(out.largest_part, std::abs(value));
  }
  return out;
}

// At the relaxed period the tiled stockinette carries no moment across a
// course cut: the terms' parts (each depends on where the cut passes) cancel,
// wherever the cut and the axis lie. At the generated period the tile pushed
// on its wale neighbours with a net force whose line of action lay below the
// cloth's mid-plane, and that force was the whole moment (a third of the
// largest part), which turned the course edges towards the back.
TEST(KnitMoment, AtTheRelaxedPeriodACourseCutCarriesNoMoment) {
  const Scene s = moment_scene("stockinette");
  const KnitModel m(s);
  ASSERT_TRUE(relaxed_tile(s).period_relaxed) << relaxed_tile(s).period_note;
  for (const double r : {3.0, 3.25, 3.5}) {
    for (const double z_ref : {0.0, s.radius_m}) {
      const Moment M = moment(m, course_cut(s, r, z_ref));
      EXPECT_GT(M.largest_part, 0.0) << "cut at row " << r << ": no element crosses it";
      EXPECT_LE(std::abs(M.total), 1e-4 * M.largest_part) << "cut at row " << r << ", axis at z = " << z_ref;
    }
  }
}

// A rigid rotation of the cloth about the cut's axis (the x axis through
// (y_c, z_ref)) turns every element's forces with it and leaves the moment
// about that axis of each term unchanged: the probe pairs each force with its
// node's position. The turn is small enough that no node changes side.
TEST(KnitMoment, TheMomentTurnsWithTheCloth) {
  const Scene s = moment_scene("garter");
  const KnitModel m(s);
  const CourseCut cut = course_cut(s, 3.0, 0.0);
  const std::map<std::string, double> at_rest = course_cut_moment(m, m.initial_q(), cut);
  Vec turned = m.initial_q();
  const double theta = 0.3, c = std::cos(theta), sn = std::sin(theta);
  for (const KnitNode& n : m.graph().nodes()) {
    const double y = turned[n.x_dof + 1] - cut.y, z = turned[n.x_dof + 2] - cut.z_ref;
    turned[n.x_dof + 1] = cut.y + c * y - sn * z;
    turned[n.x_dof + 2] = cut.z_ref + sn * y + c * z;
  }
  const std::map<std::string, double> after = course_cut_moment(m, turned, cut);
  double largest = 0.0;
  for (const auto& [name, value] : at_rest) largest = std::max(largest, std::abs(value));
  ASSERT_GT(largest, 0.0);
  for (const auto& [name, value] : at_rest) EXPECT_NEAR(after.at(name), value, 1e-9 * largest) << name;
}

// The generated stockinette path is its own image under a half turn about the
// course direction (docs/models.md §11.3.2): each loop's crown runs at the front
// and its sinker at the back, and the half turn swaps them, the face with the
// back and the cast-on with the bound-off course. So the two course edges are
// released alike but turned over: every term carries, across a cut between a
// course edge's contact row and the next, the opposite of the moment it carries
// across the other edge's cut (cuts and axis placed symmetrically; wales in the
// middle, away from the yarns' ends). Only the stitch compression's part is not
// zero there: the frame reactions of the last stitch row. Whichever way one
// course edge turns, the other turns the opposite way; real stockinette turns
// both to the front (its crowns and sinkers both lie at the back).
TEST(KnitMoment, TheStockinettesCourseEdgesAreHalfTurnImagesOfEachOther) {
  const Scene s = moment_scene("stockinette");
  const KnitModel m(s);
  const Vec q = m.initial_q();
  const int courses = s.knit->courses, wales = s.knit->wales;
  // Mean y of contact row r (both nodes of every contact), and the cloth's mid-plane.
  auto row_y = [&](int r) {
    double sum = 0.0;
    for (int k = 0; k < 4 * wales; ++k) sum += q[m.graph().node(4 * (r + 1) * wales + k).x_dof + 1];
    return sum / (4 * wales);
  };
  double z_mid = 0.0;
  for (const KnitNode& n : m.graph().nodes()) z_mid += q[n.x_dof + 2] / m.graph().num_nodes();
  CourseCut bottom = course_cut(s, 0.0, z_mid), top = bottom;
  bottom.y = 0.5 * (row_y(-1) + row_y(0));
  top.y = 0.5 * (row_y(courses - 2) + row_y(courses - 1));
  const std::map<std::string, double> at_bottom = course_cut_moment(m, q, bottom),
                                      at_top = course_cut_moment(m, q, top);
  double largest = 0.0, total_top = 0.0, total_bottom = 0.0;
  for (const auto& [name, value] : at_top) {
    largest = std::max(largest, std::abs(value));
    total_top += value;
    total_bottom += at_bottom.at(name);
  }
  ASSERT_GT(largest, 0.0);
  for (const auto& [name, value] : at_top) {
    EXPECT_NEAR(at_bottom.at(name), -value, 1e-6 * largest) << name;
    // Only the last stitch row's compression frame reaches across an edge cut with a moment.
    if (name != "stitch_compression") {
      EXPECT_LE(std::abs(value), 1e-6 * largest) << name;
    }
  }
  std::printf("moment across the course-edge cuts: bottom %.6g N m, top %.6g N m\n", total_bottom, total_top);
}

}  // namespace
}  // namespace wl
