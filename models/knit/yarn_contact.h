// Yarn–yarn contact of a knit (docs/models.md §11.10): the cloth–cloth barrier
// of the lab (self_contact.h) over the knit's yarn pieces as capsules of the
// yarn radius R, on the gap d − 2R between their centrelines. The pieces are
// the segments between consecutive visits, a stitch segment once although two
// yarns traverse it (compression_pairs.h). Which gap each pair gets:
//   - pieces that share a node are left out: the neighbours along one yarn
//     (stretch and bending hold them) and the pieces through a stitch contact
//     (the stitch terms hold them: they meet there by construction);
//   - the contact compression's pairs (§11.6), pieces of neighbouring loops
//     that pass closer than its cutoff 2R + ½ min(W, C) in the generated
//     geometry, get the barrier on their cores, the gap d − R: the
//     compression models their soft contact (a penalty that lets them overlap
//     where the pattern squeezes them, as along a free course edge; a barrier
//     on 2R too would stiffen the calibrated response and push pressed rest
//     shapes apart), the core barrier keeps them from passing through each
//     other (a penalty alone does not) and is idle until they overlap by
//     more than half a diameter less d̂;
//   - every other pair gets the gap d − 2R between the capsules. They start
//     farther apart than the cutoff (more than d̂ for any admitted d̂ < R), so
//     the barrier is idle at the rest shape and acts only where the cloth
//     folds onto itself: between loops that are not neighbours.
#pragma once
#include <memory>
#include <vector>

#include "models/common/self_contact.h"
#include "models/knit/compression_pairs.h"
#include "models/knit/knit_graph.h"

namespace wl {

struct KnitContactSet {
  ContactSurface surface;  // no triangles: every node, for its position DoFs
  ContactCapsules capsules;
};

// The contact set of an open knit: `pieces` (unique_pieces of its segments,
// no image shifts), `compressed` the compression's pairs among them (their cores in contact).
KnitContactSet knit_contact_set(const KnitGraph& graph, const std::vector<YarnPiece>& pieces,
                                const std::vector<PiecePair>& compressed, double radius);

// The core distance of the compression's pairs: R, half the capsules' 2R.
inline double knit_core_distance(double radius) { return radius; }

// The contact rule of a knit (docs/models.md §11.10): the self-contact's rule
// with the yarn radius R as the length scale (d̂ = R/2 unless set) and the
// heaviest node's mass bounded by ρ_max · 2 ℓ_max (two yarns through a node,
// ℓ_max the longest piece).
ObstacleContactRule knit_contact_rule(const Scene& scene, const KnitGraph& graph, const std::vector<YarnPiece>& pieces);

}  // namespace wl
