// Checks and helpers that both parameter optimisers (optimizer.cpp,
// target_optimizer.cpp) share.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "optimize/optimizer.hpp"

namespace ashlar {

// Throws InvalidArgument naming the first invalid setting.
void check_optimize_settings(const OptimizeSettings& settings);

// Checks parameter bounds and the start (sizes, intervals, the start within
// them; throws InvalidArgument naming the parameter) and returns each
// parameter's scale: upper - lower where that is finite and positive, else
// max(1, |initial|).
Eigen::VectorXd parameter_scales(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                 const Eigen::VectorXd& initial);

// Which bound each parameter of p sits on.
std::vector<BoundSide> active_bounds(const Eigen::VectorXd& p, const Eigen::VectorXd& lower,
                                     const Eigen::VectorXd& upper);

}  // namespace ashlar
