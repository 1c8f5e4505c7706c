// Tone mapping of rendered radiosity to 8-bit sRGB (the pictures of paper §7.4).
//
// The mapping, per channel, in this order:
//   1. exposure: divide linear radiosity by `white`. By default `white` is the 99th percentile,
//      over the pixels that see a surface, of the pixel's largest channel: at most 1 % of the
//      visible pixels (typically the emitters and what is right next to them) reach full
//      brightness, so a small bright light does not leave the rest of the picture dark;
//   2. clamp to [0, 1] (per channel: emitters and anything brighter than `white` show as full
//      white or a saturated colour; no Reinhard roll-off, so values below `white` stay linear);
//   3. the sRGB transfer function (IEC 61966-2-1: 12.92·x below 0.0031308, else
//      1.055·x^(1/2.4) − 0.055), rounded to 8 bits.
// Pixels that see nothing get kBackground, a dark blue-grey, so that a black (unlit) surface
// can be told from empty space.
#pragma once

#include <array>
#include <cstdint>
#include <functional>

#include "render/png_image.h"
#include "render/render.h"

namespace gv {

/// Percentile of visible pixel radiance that maps to 1 (see the file comment).
inline constexpr double kWhitePercentile = 0.99;
/// Colour of pixels that see no surface.
inline constexpr std::array<uint8_t, 3> kBackground{40, 44, 56};

/// The default exposure: the kWhitePercentile percentile of max(R, G, B) over the pixels that
/// see a face for which `counts(face)` is true (empty function: every face; the pictures pass
/// "not an emitter"); over all pixels seeing a face when no pixel counts; 1 when no pixel sees
/// one or the value is not positive.
double automaticWhite(const RenderBuffers& buffers,
                      const std::function<bool(uint32_t face)>& counts = {});

/// sRGB encoding of a linear value in display units (clamped to [0, 1]), to 0..255.
uint8_t encodeSrgb(double linear);

/// The tone-mapped picture (white <= 0: automaticWhite).
RgbImage toneMap(const RenderBuffers& buffers, double white = 0);

}  // namespace gv
