// Exposure by a percentile, clamp, sRGB.
#include "render/tone_map.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace gv {

double automaticWhite(const RenderBuffers& buffers,
                      const std::function<bool(uint32_t face)>& counts) {
  std::vector<double> values;
  for (int pass = 0; pass < 2 && values.empty(); ++pass)
    for (size_t i = 0; i < buffers.face.size(); ++i) {
      if (buffers.face[i] == kNoFace) continue;
      if (pass == 0 && counts && !counts(buffers.face[i])) continue;
      const Rgb& c = buffers.radiance[i];
      values.push_back(std::max({c.r, c.g, c.b}));
    }
  if (values.empty()) return 1;
  const auto k =
      static_cast<size_t>(std::floor(kWhitePercentile * static_cast<double>(values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[k] > 0 ? values[k] : 1;
}

uint8_t encodeSrgb(double linear) {
  const double x = std::clamp(std::isnan(linear) ? 0.0 : linear, 0.0, 1.0);
  const double v = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
  return static_cast<uint8_t>(std::lround(255.0 * v));
}

RgbImage toneMap(const RenderBuffers& buffers, double white) {
  if (!(white > 0)) white = automaticWhite(buffers);
  RgbImage image(buffers.width, buffers.height);
  for (int y = 0; y < buffers.height; ++y)
    for (int x = 0; x < buffers.width; ++x) {
      const size_t i = buffers.index(x, y);
      uint8_t* p = image.at(x, y);
      if (buffers.face[i] == kNoFace) {
        std::copy(kBackground.begin(), kBackground.end(), p);
        continue;
      }
      const Rgb& c = buffers.radiance[i];
      p[0] = encodeSrgb(c.r / white);
      p[1] = encodeSrgb(c.g / white);
      p[2] = encodeSrgb(c.b / white);
    }
  return image;
}

}  // namespace gv
