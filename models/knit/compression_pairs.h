// The stencil of the contact compression (docs/models.md §11.6): the yarn
// pieces of a knit (the segments between consecutive visits, a stitch segment
// once although two yarns traverse it) and the pairs of pieces it keeps apart,
// fixed at build time from the generated geometry: every two pieces that share
// no node (image) and whose generated centrelines come closer than a cutoff.
#pragma once
#include <vector>

#include "models/core/types.h"

namespace wl {

// A straight piece of yarn between node n0's image shifted by dx0 and node n1's shifted by dx1.
struct YarnPiece {
  int n0 = 0, n1 = 0;
  Vec3 dx0 = Vec3::Zero(), dx1 = Vec3::Zero();
};

// Piece a against piece b shifted by `shift` (a period of a tile, else zero).
struct PiecePair {
  int a = 0, b = 0;
  Vec3 shift = Vec3::Zero();
};

// The pieces without repeats: a piece and its reverse, or its image shifted by
// any vector, are one piece.
std::vector<YarnPiece> unique_pieces(const std::vector<YarnPiece>& pieces);

// The pairs (each once) of pieces, b taken at each of the shifts `images`
// (zero for an open cloth; the 3 × 3 nearest periods, zero included, for a
// tile), that share no node image and whose centrelines at the node positions
// `x` are closer than `cutoff`.
std::vector<PiecePair> compression_pairs(const std::vector<Vec3>& x, const std::vector<YarnPiece>& pieces,
                                         const std::vector<Vec3>& images, double cutoff);

}  // namespace wl
