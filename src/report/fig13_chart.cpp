// Inline SVG of the Fig. 13 histogram (see fig13_chart.h).
#include "report/fig13_chart.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace gv {
namespace {

constexpr double kWidth = 640, kHeight = 300;
constexpr double kLeft = 60, kRight = 20, kTop = 30, kBottom = 45;

/// A "nice" axis step (1, 2 or 5 times a power of ten) giving about `ticks` ticks up to `max`.
double niceStep(double max, int ticks) {
  const double raw = std::max(max, 1.0) / ticks;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * power >= raw) return m * power;
  return 10 * power;
}

}  // namespace

std::string fig13ChartSvg(const std::vector<uint64_t>& successes,
                          const std::vector<uint64_t>& failures) {
  const size_t lengths = std::max(successes.size(), failures.size());
  uint64_t max = 0;
  for (uint64_t v : successes) max = std::max(max, v);
  for (uint64_t v : failures) max = std::max(max, v);
  std::string svg = fmt::format(
      "<svg class=\"chart\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {} {}\" "
      "width=\"{}\" "
      "height=\"{}\" role=\"img\" aria-label=\"Fig. 13: stabbing successes and failures by "
      "sequence length\">\n",
      kWidth, kHeight, kWidth, kHeight);
  if (max == 0) {
    svg += fmt::format(
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">no stabbing tests recorded"
        "</text>\n</svg>\n",
        kWidth / 2, kHeight / 2);
    return svg;
  }
  const double plotW = kWidth - kLeft - kRight, plotH = kHeight - kTop - kBottom;
  const double step = niceStep(double(max), 5);
  const double top = std::ceil(double(max) / step) * step;
  auto y = [&](double v) { return kTop + plotH * (1 - v / top); };
  for (double v = 0; v <= top + step / 2; v += step) {
    svg += fmt::format(
        "<line x1=\"{}\" x2=\"{}\" y1=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#ddd\"/>"
        "<text x=\"{}\" y=\"{:.1f}\" text-anchor=\"end\" font-size=\"11\">{:.0f}</text>\n",
        kLeft, kLeft + plotW, y(v), y(v), kLeft - 6, y(v) + 4, v);
  }
  const double group = plotW / double(lengths);
  const double bar = group * 0.38;
  for (size_t n = 0; n < lengths; ++n) {
    const double x0 = kLeft + group * double(n) + group * 0.12;
    const uint64_t s = n < successes.size() ? successes[n] : 0;
    const uint64_t f = n < failures.size() ? failures[n] : 0;
    svg += fmt::format(
        "<rect class=\"success\" x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" "
        "height=\"{:.1f}\" fill=\"#2a9d3a\"><title>length {}: {} successes</title></rect>\n",
        x0, y(double(s)), bar, plotH - (y(double(s)) - kTop), n, s);
    svg += fmt::format(
        "<rect class=\"failure\" x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" "
        "height=\"{:.1f}\" fill=\"#c8372d\"><title>length {}: {} failures</title></rect>\n",
        x0 + bar, y(double(f)), bar, plotH - (y(double(f)) - kTop), n, f);
    svg += fmt::format(
        "<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\" font-size=\"11\">{}</text>\n",
        x0 + bar, kTop + plotH + 15, n);
  }
  svg += fmt::format("<line x1=\"{}\" x2=\"{}\" y1=\"{}\" y2=\"{}\" stroke=\"#333\"/>\n", kLeft,
                     kLeft + plotW, kTop + plotH, kTop + plotH);
  svg += fmt::format(
      "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"12\">portal "
      "sequence length</text>\n",
      kLeft + plotW / 2, kHeight - 8);
  svg += fmt::format(
      "<rect x=\"{}\" y=\"8\" width=\"10\" height=\"10\" fill=\"#2a9d3a\"/><text "
      "x=\"{}\" y=\"17\" font-size=\"12\">stabbed</text><rect x=\"{}\" y=\"8\" "
      "width=\"10\" height=\"10\" fill=\"#c8372d\"/><text x=\"{}\" y=\"17\" "
      "font-size=\"12\">not stabbed</text>\n",
      kLeft, kLeft + 14, kLeft + 90, kLeft + 104);
  svg += "</svg>\n";
  return svg;
}

}  // namespace gv
