// The growing window a long trajectory fit gets by default (docs/calibration.md §7.1).
// A window of many frames makes the cost a narrow valley that Levenberg–Marquardt
// follows in short steps, each a simulation of every frame; fitting the first few
// frames first and growing the window from each result avoids it. The default
// schedule doubles from kFirstWindowFrames (5, 10, 20, …) and ends at all frames;
// a last doubled stage within 1.5× of the whole is dropped (25 frames: 5, 10, 25).
#pragma once
#include <vector>

namespace wl {

constexpr int kLongestPlainFit = 10;   // frames fitted in one plain stage by default
constexpr int kFirstWindowFrames = 5;  // the default window's first stage

// The default growing window over `frames` fitted frames: empty (one plain stage)
// up to kLongestPlainFit frames, the doubling schedule above beyond.
std::vector<int> default_growing_window(int frames);

}  // namespace wl
