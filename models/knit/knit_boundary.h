// Pins and handles of a knit scene (docs/models.md §11.7). A scene's
// node = [i, j] names stitch contact j of contact row i: row i lies between
// course i−1 and course i (row 0 below the first course, row `courses` above
// the last), contact j is wale j/2, its left side when j is even. A pin holds
// both nodes of the contact with their sliding coordinates; a handle pulls
// both with a spring of half its stiffness each.
#pragma once
#include <array>
#include <memory>
#include <vector>

#include "models/core/term.h"
#include "models/knit/knit_graph.h"
#include "models/scene/scene.h"

namespace wl {

// The two nodes (a, b) of the contact a scene's node = [i, j] names.
std::array<int, 2> knit_contact_nodes(const KnitGraph& graph, const NodeRef& ref);
// The DoFs the scene's pins hold: positions and sliding coordinates.
std::vector<int> knit_pinned_dofs(const KnitGraph& graph, const Scene& scene);
// The scene's handles as springs from the nodes' positions in q0 (nullptr: none).
std::unique_ptr<Term> knit_handles(const KnitGraph& graph, const Scene& scene, const Vec& q0);

}  // namespace wl
