// A capability of the models that count their own intersecting primitive
// pairs (docs/design.md §3.1): the knit counts the pairs of yarn segments
// whose capsules overlap (docs/models.md §11.10). A model offers it by deriving
// from IntersectionCount besides Model; the run asks with
// intersection_count(model), null for every other model, and writes the count
// per frame into self_intersections.csv.
#pragma once
#include <string>

#include "models/core/model.h"

namespace wl {

class IntersectionCount {
 public:
  virtual ~IntersectionCount() = default;
  // The metrics column the count is written under.
  virtual std::string intersection_column() const = 0;
  // The number of intersecting pairs in state q.
  virtual long intersecting_pairs(const Vec& q) const = 0;
};

inline const IntersectionCount* intersection_count(const Model& model) {
  return dynamic_cast<const IntersectionCount*>(&model);
}

}  // namespace wl
