// The size limits of a scene that readers of its output share.
#pragma once

namespace wl {

// cloth.warps and cloth.wefts are at most kMaxYarns: node and DoF indices stay
// well inside int, and a frame has at most kMaxYarns² crossings.
inline constexpr long long kMaxYarns = 16384;

}  // namespace wl
