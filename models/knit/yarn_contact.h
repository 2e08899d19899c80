// Yarn–yarn contact of a knit (docs/models.md §11.7): the cloth–cloth barrier
// of the lab (self_contact.h) over the knit's yarn pieces as capsules of the
// yarn radius R, on the gap d − 2R between their centrelines. The pieces are
// the segments between consecutive visits, a stitch segment once although two
// yarns traverse it (compression_pairs.h). The filter leaves out the pairs that
// other terms already model:
//   - pieces that share a node: the neighbours along one yarn (stretch and
//     bending hold them) and the pieces through a stitch contact (the stitch
//     terms hold them: they meet there by construction);
//   - the contact compression's pairs (§11.6) that start in contact, with a gap
//     below d̂ at the rest shape: the pattern holds them pressed together (in
//     rib, knit and purl wales touch) and the compression models their
//     contact; a barrier on them would push the rest shape apart (the
//     distortion Gomez-Nogales et al. 2025 filter out).
// Every other pair starts with a gap of at least d̂, so the barrier is idle at
// the rest shape and acts only where the cloth folds onto itself. The
// compression's pairs that start apart keep the barrier: the compression
// acts only below the gap 0, which the barrier never lets them reach.
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

// The contact set of an open knit at its rest state q0: `pieces`
// (unique_pieces of its segments, no image shifts), `compressed` the
// compression's pairs among them, of which those with a gap below d̂ at q0 are left out.
KnitContactSet knit_contact_set(const KnitGraph& graph, const std::vector<YarnPiece>& pieces,
                                const std::vector<PiecePair>& compressed, double radius, double dhat, const Vec& q0);

// The contact rule of a knit (docs/models.md §11.7): the self-contact's rule
// with the yarn radius R as the length scale (d̂ = R/2 unless set) and the
// heaviest node's mass bounded by ρ_max · 2 ℓ_max (two yarns through a node,
// ℓ_max the longest piece).
ObstacleContactRule knit_contact_rule(const Scene& scene, const KnitGraph& graph, const std::vector<YarnPiece>& pieces);

}  // namespace wl
