// Settings of the coupled rigid-block analysis (cra.hpp), apart from the
// analysis itself so that AnalysisSettings can hold them without IPOPT or
// the analysis in its header.
#pragma once

namespace ashlar {

struct CraSettings {
  // eps: how far (as a fraction of the mean block size, the problem's unit
  // of length) a contact vertex may virtually overlap its neighbour. A
  // vertex in compression sits at exactly this overlap (its complementarity
  // constraint is f_n (d_n + eps) = 0), so it is what lets compressed
  // vertices move together. compas_cra's default is 1e-4 in model units on
  // metre-sized blocks.
  double overlap = 1e-4;
  // d_bnd: the bound on every component (normal, u, v) of a contact vertex's
  // virtual relative displacement, as a fraction of the mean block size;
  // must exceed `overlap`. compas_cra's default is 1e-3.
  double displacement_bound = 1e-3;
  // kappa: relaxes the complementarity f_n (d_n + eps) = 0 to
  // f_n (d_n + eps) <= kappa eps (forces in mean block weights Wm): a vertex
  // carrying f_n may stop short of the full overlap by kappa eps Wm / f_n:
  // one carrying kappa Wm at least touches (d_n <= 0), a much heavier one
  // sits near the full overlap, a lighter one may be open. 0 is the paper's
  // exact program, which on a hyperstatic 3D assembly (more interface
  // closure conditions than block motions) asks IPOPT to pick which
  // vertices close: on the Armadillo vault it made no progress in 240 s
  // (nor at 0.01); 0.03 and 0.1 converge. compas_cra meets it only to
  // IPOPT's absolute tolerance (1e-8 in its units of volume x 0.01), on
  // the Armadillo about kappa = 0.4; at 0.3 compas_cra's H, which falls,
  // stands. cra only: with kappa > 0 cra_penalty diverged (H.json,
  // A.json), so it keeps the exact product.
  double complementarity = 0.0;
  // cra_penalty: weight of the squared tension against the squared
  // compression and alignment terms (compas_cra's 1e6).
  double tension_weight = 1e6;
  // IPOPT's tolerances (tol, constr_viol_tol, compl_inf_tol) on the scaled
  // problem (forces in mean block weights, lengths in mean block sizes);
  // the solve also stops, as "inaccurate", at 100 times this. compas_cra
  // uses 1e-8 for its penalty form; 1e-9 made IPOPT run out of iterations
  // on a block sliding off an incline.
  double tolerance = 1e-8;
  // IPOPT's max_iter: beyond it the status is max_iterations, no verdict.
  int max_iterations = 3000;
  // Print IPOPT's iteration log (its print_level 5) to standard output.
  bool verbose = false;
};

}  // namespace ashlar
