// `weavelab_bench --scale SCENE [--model yarn|fem] [--linear-solver NAME] [--steps N] [--warmup W]`:
// time and memory of the be-linear step of one scene with one step solver, in a
// process of its own (the peak resident size is the process's): the median step,
// the resident size after each stage (model built, integrator initialized,
// steps done), the peak, and the step solver's own bytes by what holds them
// (SparseSolver::memory()). Prints one CSV header and one row (the scale study,
// experiments/scale/).
#pragma once

namespace wl::bench {

// argv without the program name and without "--scale". Returns the process
// exit code (0 ok, 2 bad arguments or scene, 1 a step failed).
int scale_main(int argc, char** argv);

}  // namespace wl::bench
