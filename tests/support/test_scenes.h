// Scene text for small end-to-end tests: an n×n upright cloth held by handles
// at its two top corners, in a 5 m/s wind, 1 ms steps and frames every 10 ms,
// with the default physics (sliding, Gong shear and friction).
#pragma once
#include <string>

namespace wl::test {

// `integrator` empty: the scene default (be-linear).
inline std::string hanging_cloth_toml(int n, double duration_s, const std::string& integrator = "") {
  const std::string last = std::to_string(n - 1);
  return "[cloth]\nwarps = " + std::to_string(n) + "\nwefts = " + std::to_string(n) +
         "\n[pose]\nkind = \"upright\"\n[[handles]]\nnode = [0, 0]\n[[handles]]\nnode = [" + last +
         ", 0]\n[wind]\nvelocity_m_per_s = [0.0, 5.0, 0.0]\nair_density_kg_per_m3 = 2.0\n[time]\nduration_s = " +
         std::to_string(duration_s) + "\ndt_s = 0.001\noutput_interval_s = 0.01\n" +
         (integrator.empty() ? "" : "integrator = \"" + integrator + "\"\n");
}

// A stockinette of `courses` × `wales` (W = 2 mm, R = 0.2 mm, sliding frozen) hung upright under
// gravity from the two top corner contacts of its cast-on row by handles of 100 N/m, 4 ms of 1 ms
// be-newton steps, frames every 2 ms (docs/models.md §11).
inline std::string hanging_knit_toml(int courses, int wales) {
  return "[cloth]\nspacing_m = 2e-3\nradius_m = 2e-4\nsliding = false\n[cloth.pattern]\nkind = \"stockinette\"\n"
         "courses = " +
         std::to_string(courses) + "\nwales = " + std::to_string(wales) +
         "\n[knit]\nroll_stiffness_N = 1e-5\n[pose]\nkind = \"upright\"\n[[handles]]\nnode = [0, 0]\n"
         "stiffness_N_per_m = 100.0\n[[handles]]\nnode = [0, " +
         std::to_string(2 * wales - 1) +
         "]\nstiffness_N_per_m = 100.0\n[time]\nduration_s = 0.004\noutput_interval_s = 0.002\n"
         "integrator = \"be-newton\"\n";
}

}  // namespace wl::test
