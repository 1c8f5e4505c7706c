// The one-line stderr progress bar: throttled redraws, elapsed time and a linear ETA.
#include "util/progress_bar.h"

#include <cstdlib>

#include <fmt/core.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace gv {

bool stderrIsTerminal() {
  return isatty(STDERR_FILENO) == 1;
}

namespace {

std::string formatSeconds(double s) {
  if (s < 60) return fmt::format("{:.1f} s", s);
  const long total = std::lround(s);
  if (total < 3600) return fmt::format("{}:{:02d}", total / 60, total % 60);
  return fmt::format("{}:{:02d}:{:02d}", total / 3600, (total / 60) % 60, total % 60);
}

}  // namespace

std::string progressLine(const std::string& label, double fraction, double elapsedSeconds) {
  const double f = std::isfinite(fraction) ? std::clamp(fraction, 0.0, 1.0) : 0.0;
  const int filled = static_cast<int>(std::floor(f * kProgressBarWidth));
  std::string line = fmt::format("{} [{}{}] {:5.1f} %  {}", label, std::string(filled, '#'),
                                 std::string(kProgressBarWidth - filled, '.'), 100 * f,
                                 formatSeconds(elapsedSeconds));
  if (f > 0 && f < 1) line += "  ETA " + formatSeconds(elapsedSeconds * (1 - f) / f);
  return line;
}

double progressFirstDrawSeconds() {
  static const double seconds = [] {
    const char* v = std::getenv("GLOBALVIS_PROGRESS_DELAY");
    if (!v || !*v) return kProgressFirstDrawSeconds;
    char* end = nullptr;
    const double d = std::strtod(v, &end);
    return (end && *end == '\0' && d >= 0 && std::isfinite(d)) ? d : kProgressFirstDrawSeconds;
  }();
  return seconds;
}

ProgressBar::ProgressBar(std::string label, bool enabled, std::FILE* out, double firstDrawSeconds)
    : label_(std::move(label)),
      enabled_(enabled && out != nullptr),
      out_(out),
      firstDrawSeconds_(firstDrawSeconds) {}

ProgressBar::~ProgressBar() {
  // An abandoned stage (an exception) leaves its bar where it was, on a line of its own.
  if (enabled_ && drawn_ && !finished_) fmt::print(out_, "\n");
}

void ProgressBar::update(size_t done, size_t total) {
  update(total == 0 ? 1.0 : static_cast<double>(done) / static_cast<double>(total));
}

void ProgressBar::update(double fraction) {
  if (!enabled_ || finished_) return;
  fraction_ = fraction;
  // The last update ends the line, so the next output starts on a fresh one.
  if (fraction >= 1) return finish();
  const auto now = Clock::now();
  if (!drawn_ && std::chrono::duration<double>(now - start_).count() < firstDrawSeconds_) return;
  if (drawn_ && fraction < 1 &&
      std::chrono::duration<double>(now - lastDraw_).count() < kProgressRedrawSeconds)
    return;
  draw(fraction);
}

void ProgressBar::note(const std::string& line) {
  if (!enabled_) return;
  if (!drawn_) {
    fmt::print(out_, "{}\n", line);
    return;
  }
  fmt::print(out_, "\r{}\r{}\n", std::string(lastWidth_, ' '), line);
  lastWidth_ = 0;
  if (!finished_) draw(fraction_);
}

void ProgressBar::finish() {
  if (!enabled_ || finished_) return;
  finished_ = true;
  if (!drawn_) return;  // over before it was worth showing
  draw(1.0);
  fmt::print(out_, "\n");
  std::fflush(out_);
  lastWidth_ = 0;  // the cursor is on a fresh line
}

std::function<void(size_t, size_t)> ProgressBar::callback() {
  if (!enabled_) return {};
  return [this](size_t done, size_t total) { update(done, total); };
}

void ProgressBar::draw(double fraction) {
  const std::string line = progressLine(label_, fraction, secondsSince(start_));
  // Pad over the previous line's tail (the ETA may get shorter).
  const size_t pad = lastWidth_ > line.size() ? lastWidth_ - line.size() : 0;
  fmt::print(out_, "\r{}{}", line, std::string(pad, ' '));
  std::fflush(out_);
  lastWidth_ = line.size();
  lastDraw_ = Clock::now();
  drawn_ = true;
}

}  // namespace gv
