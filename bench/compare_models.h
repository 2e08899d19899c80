// `weavelab_bench --compare-models [SCENE] [--steps N] [--yarn-steps M]`:
// the FEM and yarn backward-Euler (be-linear) step times on one scene, and the
// FEM step against its own factor+solve (target: at most 2×), in one run.
#pragma once

namespace wl::bench {

// argv without the program name and without "--compare-models". Returns the
// process exit code (0 ok, 2 bad arguments or scene, 1 a step failed).
int compare_models_main(int argc, char** argv);

}  // namespace wl::bench
