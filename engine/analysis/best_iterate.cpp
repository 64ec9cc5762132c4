#include "analysis/best_iterate.hpp"

#include <cmath>
#include <utility>

namespace ashlar {

namespace {

// Iterations without a more accurate iterate, once one is within the
// inaccurate tolerance, after which the solve stops; and at any accuracy,
// after which more iterations are not going to help.
constexpr int kStallIterations = 8;
constexpr int kHopelessIterations = 20;

}  // namespace

BestIterate::BestIterate(const InteriorPointSolution& iterate, const NewtonVectors& direction,
                         double inaccurate_tolerance)
    : iterate_(iterate), direction_(direction), inaccurate_tolerance_(inaccurate_tolerance) {}

void BestIterate::begin(int iteration) {
  previous_is_best_ = !copied_ && std::isfinite(error_) && iteration_ == iteration - 1;
}

void BestIterate::keep_previous() {
  if (previous_is_best_) copy_previous();
}

void BestIterate::note(int iteration, double error, bool counts, const InteriorPointInfo& info) {
  if (counts && error < least_error_) {
    least_error_ = error;
    least_error_iteration_ = iteration;
  }
  if (counts && error <= inaccurate_tolerance_ && error < error_) {
    error_ = error;
    iteration_ = iteration;
    info_ = info;
    if (copied_) {  // an older copy is no longer needed
      copied_ = false;
      for (Eigen::VectorXd* v : {&copy_.x, &copy_.y, &copy_.w, &copy_.z}) v->resize(0);
    }
  } else if (previous_is_best_) {
    copy_previous();
  }
}

bool BestIterate::stalled(int iteration) const {
  const int stalled = iteration - least_error_iteration_;
  return (least_error_ <= inaccurate_tolerance_ && stalled > kStallIterations) || stalled > kHopelessIterations;
}

void BestIterate::copy_previous() {
  copy_.x = iterate_.x - last_step_.primal * direction_.x;
  copy_.y = iterate_.y - last_step_.dual * direction_.y;
  copy_.w = iterate_.w - last_step_.primal * direction_.w;
  copy_.z = iterate_.z - last_step_.dual * direction_.z;
  copied_ = true;
  if (!copy_.x.allFinite() || !copy_.y.allFinite() || !copy_.w.allFinite() || !copy_.z.allFinite()) {
    error_ = std::numeric_limits<double>::infinity();
  }
}

// Short of convergence (or of a certificate, which is the iterate it
// stopped at) the most accurate iterate within the inaccurate tolerance is
// the answer, and says so; without one, the last iterate stays, with its
// status. An interrupted solve stays interrupted: it carries no verdict.
void BestIterate::restore(InteriorPointInfo& info, InteriorPointSolution& solution) {
  if (info.status == SolverStatus::converged || info.status == SolverStatus::certified || !std::isfinite(error_)) {
    return;
  }
  const int iterations = info.iterations;
  const SolverStatus status = info.status;
  info = info_;
  info.iterations = iterations;
  info.status = status == SolverStatus::interrupted ? status : SolverStatus::inaccurate;
  if (copied_) {  // else the best is the iterate the solve stopped at
    solution = std::move(copy_);
  }
}

}  // namespace ashlar
