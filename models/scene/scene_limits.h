// The limits of a scene that readers of its output and the command line share.
#pragma once

namespace wl {

// cloth.warps and cloth.wefts are at most kMaxYarns: node and DoF indices stay
// well inside int, and a frame has at most kMaxYarns² crossings.
inline constexpr long long kMaxYarns = 16384;

// The smallest relative tolerance of error control, whether read from a scene
// (time.rtol) or given on a command line (--rtol of every subcommand): below it
// (about 10⁴ ε) a step's round-off is a sizeable part of the tolerance, and
// error control asked for less cannot deliver it.
inline constexpr double kMinRtol = 1e-12;

}  // namespace wl
