// The most accurate interior-point iterate within the inaccurate tolerance
// (InteriorPointSettings::inaccurate_tolerance), and when the iterations
// have stalled.
//
// When rounding stops the iterations short of the tolerance (active
// constraints whose slacks fall to 1e-12), that iterate is the answer,
// reported as inaccurate. It is copied only once a later iterate is less
// accurate, by undoing the step that left it: while the error falls, as it
// does near the optimum of almost every solve, no copy exists (160 MB on a
// 100,052-block vault, whose error also rises in its early iterations).
// The least error at any accuracy only tells when the solve has stalled.
//
// Errors are the scaled errors of iterate_residuals.hpp; iterates and
// directions are shaped as in interior_point_iterate.hpp.
#pragma once

#include <Eigen/Core>
#include <limits>

#include "analysis/interior_point.hpp"
#include "analysis/interior_point_iterate.hpp"
#include "analysis/step_policy.hpp"

namespace ashlar {

class BestIterate {
public:
  // Of the iterations that step `iterate` along `direction`; both must
  // outlive this.
  BestIterate(const InteriorPointSolution& iterate, const NewtonVectors& direction, double inaccurate_tolerance);

  // At the start of iteration `iteration`, before note().
  void begin(int iteration);
  // The step just taken (`direction` holds its direction until the next).
  void stepped(const StepLengths& lengths) { last_step_ = lengths; }
  // The iterate could not be measured (not finite): the one before the last
  // step is kept if it was the best.
  void keep_previous();
  // The iterate's scaled error and its info; `counts` is false for a cold
  // start's first point, which only feeds Mehrotra's starting heuristic.
  void note(int iteration, double error, bool counts, const InteriorPointInfo& info);
  // Whether the solve should give up: no more accurate iterate for a while,
  // a short while once one is within the inaccurate tolerance.
  bool stalled(int iteration) const;
  // After a solve that ended short of convergence with `info` (status set):
  // when there is a best iterate, it goes into `solution` (unless it is the
  // one the solve stopped at) and its info into `info`, status inaccurate
  // (interrupted stays interrupted) and the iterations taken kept.
  void restore(InteriorPointInfo& info, InteriorPointSolution& solution);

private:
  // Copies the iterate before the last step as the best; it is lost if
  // that is not finite.
  void copy_previous();

  const InteriorPointSolution& iterate_;
  const NewtonVectors& direction_;
  const double inaccurate_tolerance_;
  StepLengths last_step_;
  double least_error_ = std::numeric_limits<double>::infinity();
  int least_error_iteration_ = 0;
  // The best iterate: its error, iteration and info, and the copy of it
  // when it is neither the current iterate nor the one before the last step.
  double error_ = std::numeric_limits<double>::infinity();
  int iteration_ = 0;
  bool copied_ = false;
  bool previous_is_best_ = false;  // at begin(): the best is the iterate before the last step, not copied
  InteriorPointSolution copy_;
  InteriorPointInfo info_;
};

}  // namespace ashlar
