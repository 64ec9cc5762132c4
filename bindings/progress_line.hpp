// The `progress` option of long analyses (default: when stderr is a
// terminal): a line on stderr counting what is done (blocks, digits),
// redrawn in place on a terminal, with a closing line. It is drawn from
// the first report at least `delay` seconds after it was set up: a
// computation that ends sooner draws nothing.
#pragma once

#include <unistd.h>

#include <optional>
#include <string>
#include <utility>

#include "core/clock.hpp"
#include "core/progress.hpp"
#include "luax.hpp"
#include "study/study_progress.hpp"

namespace ashlar::lua {

class ProgressLine {
public:
  // kind: the analysis ("load_capacity"); label: what it works on ("305
  // blocks"); unit: what is counted ("block").
  ProgressLine(const OptionTable& options, std::string kind, std::string label, std::string unit,
               double delay = 0.0)
      : enabled_(options.boolean("progress").value_or(isatty(STDERR_FILENO) != 0)),
        kind_(std::move(kind)),
        label_(std::move(label)),
        unit_(std::move(unit)),
        delay_(delay) {}

  ProgressCount callback() {
    if (!enabled_) return {};
    return [this](int done, int total) {
      done_ = done;
      // Set up at the first report (its rate counts from there), drawn once the delay is past.
      if (!line_) {
        const std::size_t all =
            total == kTotalUnknown ? study::StudyProgress::kUnknownTotal : static_cast<std::size_t>(total);
        line_.emplace(label_, all, true, stderr, 10.0, kind_, unit_);
      }
      if (seconds_since(start_) < delay_) return;
      drawn_ = true;
      line_->update(static_cast<std::size_t>(done), 0);
    };
  }
  void finish(const std::string& status) {
    if (drawn_) line_->finish(static_cast<std::size_t>(done_), 0, status);
  }

private:
  bool enabled_;
  std::string kind_, label_, unit_;
  double delay_;
  Clock::time_point start_ = Clock::now();
  std::optional<study::StudyProgress> line_;
  int done_ = 0;
  bool drawn_ = false;
};

}  // namespace ashlar::lua
