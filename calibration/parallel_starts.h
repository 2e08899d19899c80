// Independent fit starts run `threads` at a time (docs/calibration.md §7): each
// call of solve(s) owns what it touches, so the results do not depend on the
// thread count or the order.
#pragma once
#include <functional>

namespace wl {

// Calls solve(s) for s = 0 … count − 1 on up to `threads` threads (≤ 1: in
// order on the calling thread). The first exception a call throws stops the
// others from starting and is rethrown here.
void run_starts(int count, int threads, const std::function<void(int)>& solve);

}  // namespace wl
