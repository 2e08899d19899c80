// The yarn pairs of a stitch contact (docs/models.md §11.1, §11.4, §11.6):
// its nodes carry n ≥ 2 yarns in slots ordered as the yarns lie through the
// cloth (a stacked stitch when n ≥ 3, a decrease). Every two yarns at the
// contact are a pair, each pair once (slots i < j, in the order (0, 1), (0, 2),
// …, (1, 2), …), and the pair's centrelines lie the share (j − i)/(n − 1) of
// the stack's height apart (n = 2: the one pair (0, 1), share 1).
#pragma once
#include <vector>

namespace wl {

struct StackPair {
  int i = 0, j = 1;    // slots
  double share = 1.0;  // (j − i)/(n − 1)
};

inline std::vector<StackPair> stack_pairs(int yarns) {
  std::vector<StackPair> pairs;
  for (int i = 0; i < yarns; ++i)
    for (int j = i + 1; j < yarns; ++j) pairs.push_back({i, j, static_cast<double>(j - i) / (yarns - 1)});
  return pairs;
}

}  // namespace wl
