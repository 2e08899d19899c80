// The moment a knit carries across a course cut, term by term (docs/models.md
// §11.3.2): at a state q of a flat knit (courses along +y, the face towards +z),
// the plane y = y_c splits the nodes into those below and those above; every
// element with nodes on both sides carries, onto the part above, the moment
// about the course direction x through (y_c, z_ref) of its forces there,
//   M = Σ_{nodes above} (y − y_c) f_z − (z − z_ref) f_y.
// An element whose nodes lie on one side carries nothing across. At a periodic
// equilibrium the sum over the terms is what a course edge cut there releases;
// the parts say which term carries it there (they depend on where the cut
// passes, their sum does not). An open cloth: a periodic tile's image shifts
// are not read.
#pragma once
#include <map>
#include <string>

#include "models/core/types.h"

namespace wl {

class KnitModel;

struct CourseCut {
  double y = 0.0;                   // y_c [m]
  double z_ref = 0.0;               // z of the moment's axis [m] (the cloth's mid-plane)
  double x_min = 0.0, x_max = 0.0;  // only elements whose nodes' mean x lies in [x_min, x_max)
};

// Per term name (terms of one name summed): M [N·m] of the elements in the window.
std::map<std::string, double> course_cut_moment(const KnitModel& model, const Vec& q, const CourseCut& cut);

}  // namespace wl
