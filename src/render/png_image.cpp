// PNG files through libpng's simplified API.
#include "render/png_image.h"

#include <png.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>

#include "util/input_error.h"

namespace gv {

namespace {

/// zlib level 1 of 9: pictures of flat-shaded interiors compress almost as well as at the
/// default level, several times faster (writing was most of the picture time at level 6).
constexpr int kCompressionLevel = 1;

[[noreturn]] void throwPngError(png_structp png, png_const_charp message) {
  *static_cast<std::string*>(png_get_error_ptr(png)) = message;
  png_longjmp(png, 1);
}

void warnNothing(png_structp, png_const_charp) {}

}  // namespace

namespace {

/// Writes the PNG stream; false when libpng reported an error (longjmp back here). Nothing
/// local is modified between setjmp and a longjmp, so nothing is clobbered.
bool writeStream(png_structp png, png_infop info, FILE* file, const RgbImage& image) {
  if (setjmp(png_jmpbuf(png)) != 0) return false;
  png_init_io(png, file);
  png_set_compression_level(png, kCompressionLevel);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
               static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y) png_write_row(png, image.at(0, y));
  png_write_end(png, nullptr);
  return true;
}

}  // namespace

void writePng(const RgbImage& image, const std::string& path) {
  FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) throw InputError(path, 0, std::string("cannot write PNG: ") + std::strerror(errno));
  std::string error;
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, &throwPngError, &warnNothing);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  bool ok = png && info && writeStream(png, info, file, image);
  if (!ok && error.empty()) error = "libpng failed";
  png_destroy_write_struct(png ? &png : nullptr, info ? &info : nullptr);
  if (std::fclose(file) != 0 && ok) ok = false, error = std::strerror(errno);
  if (!ok) throw InputError(path, 0, "cannot write PNG: " + error);
}

RgbImage readPng(const std::string& path) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str()))
    throw InputError(path, 0, std::string("cannot read PNG: ") + png.message);
  png.format = PNG_FORMAT_RGB;
  RgbImage image(static_cast<int>(png.width), static_cast<int>(png.height));
  if (!png_image_finish_read(&png, nullptr, image.pixels.data(), 0, nullptr)) {
    const std::string message = png.message;
    png_image_free(&png);
    throw InputError(path, 0, "cannot read PNG: " + message);
  }
  return image;
}

}  // namespace gv
