// Data for the experiment driver tests: a 5×5 hanging cloth scene, random
// trajectories and CSV rows as cells.
#pragma once
#include <Eigen/Core>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "driver/recorded_run.h"
#include "models/scene/scene.h"
#include "tests/output/output_test_util.h"

namespace wl::test {

inline Trajectory random_trajectory(int nodes, int times, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  Trajectory t;
  for (int k = 0; k < times; ++k) t.times.push_back(1e-3 * (k + 1));
  t.positions.resize(3 * nodes, times);
  for (Eigen::Index i = 0; i < t.positions.size(); ++i) t.positions.data()[i] = u(rng);
  return t;
}

// A 5×5 hanging cloth (two top corners held), 4 ms with outputs every 2 ms.
inline std::string tiny_scene_text(double duration = 0.004) {
  std::ostringstream s;
  s << "[cloth]\nwarps = 5\nwefts = 5\n"
    << "[pose]\nkind = \"upright\"\nheight_m = 0.02\n"
    << "[[handles]]\nnode = [0, 0]\nstiffness_N_per_m = 1.0e4\n"
    << "[[handles]]\nnode = [4, 0]\nstiffness_N_per_m = 1.0e4\n"
    << "[wind]\nvelocity_m_per_s = [0.0, 5.0, 0.0]\nair_density_kg_per_m3 = 2.0\ndrag_Ns_per_m3 = 0.5\n"
    << "[time]\nduration_s = " << duration << "\noutput_interval_s = 0.002\n";
  return s.str();
}

// Points an experiment's configuration at the tiny scene (scene_path, scene_text, scene).
template <class Config>
void use_tiny_scene(Config& c) {
  c.scene_path = "tiny.toml";
  c.scene_text = tiny_scene_text();
  c.scene = parse_scene(c.scene_text, "tiny.toml");
}

// Every CSV line as cells (no quoted commas in the columns read here).
inline std::vector<std::vector<std::string>> read_csv(const std::filesystem::path& p) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(p);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string c;
    while (std::getline(ss, c, ',')) cells.push_back(c);
    rows.push_back(cells);
  }
  return rows;
}

// Runs a chart script on a result folder; `script` is its path in the repository
// (e.g. experiments/stability/scripts/plot_stability.py).
inline CommandResult run_chart_script(const std::string& script, const std::filesystem::path& folder) {
  const std::string path = std::string(WEAVELAB_SOURCE_DIR) + "/" + script;
  return run_command(std::string(python()) + " " + shell_quote(path) + " " + shell_quote(folder.string()));
}

}  // namespace wl::test
