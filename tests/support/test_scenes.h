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

}  // namespace wl::test
