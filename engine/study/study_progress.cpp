#include "study/study_progress.hpp"

#include <algorithm>
#include <cmath>

#include <unistd.h>

#include "core/process_stats.hpp"

namespace ashlar::study {

StudyProgress::StudyProgress(std::string label, std::size_t total, bool enabled, std::FILE* out,
                             double log_interval, std::string kind, std::string unit)
    : label_(std::move(label)),
      kind_(std::move(kind)),
      unit_(std::move(unit)),
      total_(total),
      enabled_(enabled && out != nullptr),
      terminal_(enabled_ && isatty(fileno(out))),
      out_(out),
      log_interval_(log_interval),
      start_(monotonic_seconds()) {}

std::string StudyProgress::clock_text(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  const long whole = std::lround(seconds);
  char buffer[32];
  if (whole < 60) std::snprintf(buffer, sizeof buffer, "%ld s", whole);
  else if (whole < 3600) std::snprintf(buffer, sizeof buffer, "%ld:%02ld", whole / 60, whole % 60);
  else std::snprintf(buffer, sizeof buffer, "%ld:%02ld:%02ld", whole / 3600, whole / 60 % 60, whole % 60);
  return buffer;
}

std::string StudyProgress::status_text(std::size_t done, std::size_t errors, double elapsed) const {
  const double rate = elapsed > 0 ? static_cast<double>(done) / elapsed : 0.0;
  if (total_ == kUnknownTotal) {
    char buffer[160];
    std::snprintf(buffer, sizeof buffer, "%zu %ss  %.1f %ss/s  %s", done, unit_.c_str(), rate, unit_.c_str(),
                  clock_text(elapsed).c_str());
    return buffer;
  }
  const double eta = rate > 0 ? static_cast<double>(total_ - std::min(done, total_)) / rate : NAN;
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, "%zu/%zu %3.0f%%  %.1f %ss/s  ETA %s", done, total_,
                total_ ? 100.0 * static_cast<double>(done) / static_cast<double>(total_) : 100.0, rate,
                unit_.c_str(), clock_text(eta).c_str());
  std::string text = buffer;
  if (errors) text += "  " + std::to_string(errors) + (errors == 1 ? " error" : " errors");
  return text;
}

void StudyProgress::update(std::size_t done, std::size_t errors) {
  if (!enabled_) return;
  const double now = monotonic_seconds();
  const double interval = terminal_ ? 0.1 : log_interval_;
  if (last_draw_ >= 0 && now - last_draw_ < interval) return;
  last_draw_ = now;
  const std::string status = status_text(done, errors, now - start_);
  if (terminal_ && total_ == kUnknownTotal) {  // no bar to tell what is running: the kind says it
    std::fprintf(out_, "\r\033[K%s %s: %s", kind_.c_str(), label_.c_str(), status.c_str());
  } else if (terminal_) {
    constexpr int kBarWidth = 24;
    const int filled = total_ ? static_cast<int>(kBarWidth * std::min(done, total_) / total_) : kBarWidth;
    const std::string bar = std::string(filled, '#') + std::string(kBarWidth - filled, '.');
    std::fprintf(out_, "\r\033[K%s [%s] %s", label_.c_str(), bar.c_str(), status.c_str());
  } else {
    std::fprintf(out_, "%s %s: %s\n", kind_.c_str(), label_.c_str(), status.c_str());
  }
  std::fflush(out_);
}

void StudyProgress::finish(std::size_t done, std::size_t errors, const std::string& note) {
  if (!enabled_) return;
  const double elapsed = monotonic_seconds() - start_;
  const double rate = elapsed > 0 ? static_cast<double>(done) / elapsed : 0.0;
  std::fprintf(out_, "%s%s %s: %zu %s%s in %s (%.1f %ss/s), %zu %s%s%s\n", terminal_ ? "\r\033[K" : "",
               kind_.c_str(), label_.c_str(), done, unit_.c_str(), done == 1 ? "" : "s", clock_text(elapsed).c_str(),
               rate, unit_.c_str(), errors, errors == 1 ? "error" : "errors", note.empty() ? "" : "; ", note.c_str());
  std::fflush(out_);
}

}  // namespace ashlar::study
