// The stiffness a step matrix takes from a term that projects it
// (Term::projects_step_stiffness, docs/models.md §3.11.2): the element's
// stiffness H = −K_e (symmetric) replaced by its positive semi-definite part
// H₊ = V max(Λ, 0) Vᵀ, as incremental potential contact projects each contact
// Hessian for its Newton solves (Li et al. 2020). Where H ⪰ 0 it is unchanged.
#pragma once

namespace wl {

// Replaces the n×n column-major block k = K_e by −(−K_e)₊ in place; k must be
// symmetric. A zero block is left as it is.
void project_step_stiffness(int n, double* k);

}  // namespace wl
