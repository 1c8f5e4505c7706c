// A one-line progress bar on stderr for the stages that take more than a second (BSP,
// propagation, radiosity refinement, PVS): drawn only on a terminal, at most ~10 times a second.
#pragma once

#include <cstddef>
#include <cstdio>
#include <functional>
#include <string>

#include "util/timing.h"

namespace gv {

/// Redraws closer together than this are skipped (the bar would only flicker).
inline constexpr double kProgressRedrawSeconds = 0.1;

/// A stage that ends sooner than this after its bar was made never shows it: most stages take
/// milliseconds on small scenes, and a bar flashing by is noise.
inline constexpr double kProgressFirstDrawSeconds = 0.5;

/// The delay before a bar first shows: kProgressFirstDrawSeconds, or the environment variable
/// GLOBALVIS_PROGRESS_DELAY (seconds, >= 0) when set, e.g. 0 to see every stage's bar (tests
/// use it so that they do not depend on how fast the machine is).
double progressFirstDrawSeconds();

/// Cells of the bar between its brackets.
inline constexpr int kProgressBarWidth = 30;

/// True when stderr is a terminal (the only place a `\r`-redrawn bar belongs).
bool stderrIsTerminal();

/// The bar's text without the leading `\r`: "label [#####.....]  42.0 %  3.1 s  ETA 4.2 s".
/// `fraction` is clamped to [0, 1]; the ETA is left out while nothing is done.
std::string progressLine(const std::string& label, double fraction, double elapsedSeconds);

/// One stage's progress. Disabled bars do nothing at all, so callers need no `if`.
class ProgressBar {
 public:
  /// A bar labelled `label` drawn on `out` when `enabled` (by default: stderr is a terminal),
  /// first drawn `firstDrawSeconds` after construction.
  explicit ProgressBar(std::string label, bool enabled = stderrIsTerminal(),
                       std::FILE* out = stderr,
                       double firstDrawSeconds = progressFirstDrawSeconds());
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// Reports `done` of `total` units; redraws when kProgressRedrawSeconds have passed, and
  /// always at 100 %, which finishes the bar.
  void update(size_t done, size_t total);
  /// Reports a fraction in [0, 1] of the work done.
  void update(double fraction);
  /// Prints `line` on its own line (clearing the bar first), then redraws the bar.
  void note(const std::string& line);
  /// Draws 100 % and ends the line if the bar was shown; later updates are ignored. (The
  /// destructor only ends the line of a bar left unfinished, e.g. by an exception.)
  void finish();
  bool enabled() const { return enabled_; }
  /// `update(done, total)` as a callback, for PropagationOptions::progress and the like;
  /// empty when the bar is disabled (so the stage skips its bookkeeping too).
  std::function<void(size_t, size_t)> callback();

 private:
  void draw(double fraction);

  std::string label_;
  bool enabled_;
  std::FILE* out_;
  double firstDrawSeconds_;
  Clock::time_point start_ = Clock::now();
  Clock::time_point lastDraw_{};
  bool drawn_ = false, finished_ = false;
  double fraction_ = 0;
  size_t lastWidth_ = 0;
};

}  // namespace gv
