#include "analysis/parameter_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "core/clock.hpp"

namespace ashlar {

namespace {

// |value - reference| / |reference|; a zero reference is only matched exactly.
double relative_difference(double value, double reference) {
  if (reference == 0.0) return value == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
  return std::abs(value - reference) / std::abs(reference);
}

}  // namespace

const char* threshold_status_name(ThresholdStatus status) {
  return kThresholdStatusNames.name(status);
}

Threshold find_threshold(double start, const ThresholdSettings& settings,
                         const std::function<ThresholdVerdict(double)>& criterion) {
  Threshold t;
  auto probe = [&](double value) {
    const auto probe_start = Clock::now();
    ThresholdProbe p;
    p.value = value;
    p.verdict = criterion(value);
    p.seconds = seconds_since(probe_start);
    ++t.evaluations;
    (p.verdict.stands ? t.stable : t.unstable) = value;
    t.history.push_back(std::move(p));
  };
  auto exhausted = [&] { return t.evaluations >= settings.max_evaluations; };
  auto finish = [&](ThresholdStatus status) {
    t.status = status;
    return t;
  };
  probe(start);
  while (std::isnan(t.unstable)) {
    if (t.stable <= settings.floor) return finish(ThresholdStatus::stable_at_lower);
    if (exhausted()) return finish(ThresholdStatus::max_analyses);
    probe(std::max(0.5 * t.stable, settings.floor));
  }
  while (std::isnan(t.stable)) {
    if (t.unstable >= settings.ceiling) return finish(ThresholdStatus::unstable_at_upper);
    if (exhausted()) return finish(ThresholdStatus::max_analyses);
    probe(std::min(2.0 * t.unstable, settings.ceiling));
  }
  while (t.stable - t.unstable > settings.bracket_tolerance * t.stable) {
    if (exhausted()) return finish(ThresholdStatus::max_analyses);
    probe(0.5 * (t.unstable + t.stable));
  }
  return finish(ThresholdStatus::converged);
}

Refinement refine_count(const RefineSettings& settings, const std::function<double(int)>& metric) {
  Refinement out;
  int settled = 0;
  for (int count = settings.start;;) {
    const auto start = Clock::now();
    RefineStep step;
    step.count = count;
    step.value = metric(count);
    step.seconds = seconds_since(start);
    if (!out.history.empty()) {
      step.change = relative_difference(out.history.back().value, step.value);
      settled = step.change <= settings.tolerance ? settled + 1 : 0;
    }
    out.history.push_back(step);
    if (settled >= settings.confirm) {
      out.converged = true;
      break;
    }
    if (count >= settings.max) break;
    const double next = std::max(count + 1.0, std::ceil(count * settings.growth));
    count = static_cast<int>(std::min(next, static_cast<double>(settings.max)));
  }
  out.adequate = out.history.size() - 1;
  if (out.converged) {
    const double reference = out.history.back().value;
    while (out.adequate > 0 &&
           relative_difference(out.history[out.adequate - 1].value, reference) <=
               settings.tolerance) {
      --out.adequate;
    }
  }
  return out;
}

}  // namespace ashlar
