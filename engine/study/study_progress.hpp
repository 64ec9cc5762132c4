// How a running study reports itself: on a terminal, one line redrawn in
// place (bar, count, rate, ETA, errors); otherwise (a log file, CI) a plain
// line every `log_interval` seconds and at the end.
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>

namespace ashlar::study {

class StudyProgress {
public:
  // A total not known ahead (a solver's iterations): the line then shows
  // the count, the rate and the time so far, without a bar or an ETA.
  static constexpr std::size_t kUnknownTotal = static_cast<std::size_t>(-1);

  // total: runs this session will do; out: where to write (stderr by
  // default); enabled = false writes nothing. `kind` begins the lines
  // written off a terminal and the closing line ("study <label>: ..."), and
  // `unit` names what is counted ("run": "12 runs", "3.5 runs/s"), so that
  // other long loops (a simulation's steps) report the same way.
  StudyProgress(std::string label, std::size_t total, bool enabled, std::FILE* out = stderr,
                double log_interval = 10.0, std::string kind = "study", std::string unit = "run");

  // Called as runs finish; redraws at most 10 times a second.
  void update(std::size_t done, std::size_t errors);
  // The closing line: runs, time, rate, errors, and why it stopped early if it did.
  void finish(std::size_t done, std::size_t errors, const std::string& note = "");

  // "1:02:03", "4:05" or "7 s" for a duration in seconds.
  static std::string clock_text(double seconds);

private:
  std::string status_text(std::size_t done, std::size_t errors, double elapsed) const;

  std::string label_, kind_, unit_;
  std::size_t total_;
  bool enabled_, terminal_;
  std::FILE* out_;
  double log_interval_;
  double start_, last_draw_ = -1.0;
};

}  // namespace ashlar::study
