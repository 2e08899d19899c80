// The header of the tile law the tile-law tests share (models/fem/tile_law_file.h):
// W₀ = 1.5 J/m²; s = (0.02, 0.02, 0.5, 10, 10, 10); the sampled box
// ε_u, ε_v ∈ [−0.005, 0.02], γ ∈ [−0.5, 0.5], κ_u, κ_v, κ_uv ∈ [−10, 10]. Its rows are
// lines 1–20 of the file, so a law's first monomial is line 21.
#pragma once
#include <string>

namespace wl::test {

inline const std::string kTileLawHeader =
    "name,value\nenergy_scale_J_per_m2,1.5\n"
    "scale:stretch_warp,0.02\nscale:stretch_weft,0.02\nscale:shear,0.5\n"
    "scale:curvature_warp,10\nscale:curvature_weft,10\nscale:twist,10\n"
    "lo:stretch_warp,-0.005\nlo:stretch_weft,-0.005\nlo:shear,-0.5\nlo:curvature_warp,-10\nlo:curvature_weft,-10\n"
    "lo:twist,-10\nhi:stretch_warp,0.02\nhi:stretch_weft,0.02\nhi:shear,0.5\nhi:curvature_warp,10\n"
    "hi:curvature_weft,10\nhi:twist,10\n";

}  // namespace wl::test
