// 8-bit RGB images and their PNG files (libpng), for the radiosity pictures (paper §7.4).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace gv {

/// An 8-bit sRGB image, rows top to bottom, 3 bytes (R, G, B) per pixel.
struct RgbImage {
  int width = 0, height = 0;
  std::vector<uint8_t> pixels;  ///< 3 * width * height

  RgbImage() = default;
  RgbImage(int w, int h) : width(w), height(h), pixels(3 * static_cast<size_t>(w) * h, 0) {}
  uint8_t* at(int x, int y) { return &pixels[3 * (static_cast<size_t>(y) * width + x)]; }
  const uint8_t* at(int x, int y) const {
    return &pixels[3 * (static_cast<size_t>(y) * width + x)];
  }
};

/// Writes `image` as an 8-bit RGB PNG. Throws InputError (path, line 0) when it cannot.
void writePng(const RgbImage& image, const std::string& path);

/// Reads a PNG (any colour type libpng can convert) as 8-bit RGB. Throws InputError (path,
/// line 0) when the file is missing or not a PNG.
RgbImage readPng(const std::string& path);

}  // namespace gv
