#include "analysis/qps_export.hpp"

#include "core/error.hpp"

namespace ashlar {

std::string equilibrium_qps(const EquilibriumProblem&, const std::string&) {
  throw Error("QPS export is not built yet");
}

void write_equilibrium_qps(const EquilibriumProblem& problem, const std::string& path) {
  equilibrium_qps(problem, path);
}

}  // namespace ashlar
