#include "calibration/fit_continuation.h"

namespace wl {

std::vector<int> default_growing_window(int frames) {
  if (frames <= kLongestPlainFit) return {};
  std::vector<int> window{kFirstWindowFrames};
  while (2 * window.back() < frames) window.push_back(2 * window.back());
  if (window.size() > 1 && 2 * frames < 3 * window.back()) window.pop_back();
  window.push_back(frames);
  return window;
}

}  // namespace wl
