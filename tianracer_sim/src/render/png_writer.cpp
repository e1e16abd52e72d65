#include "tianracer_sim/render/png_writer.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>

#include <png.h>

namespace tianracer_sim {
namespace {

struct PngFile {
  FILE* file = nullptr;
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~PngFile() {
    if (png != nullptr) png_destroy_write_struct(&png, info != nullptr ? &info : nullptr);
    if (file != nullptr) std::fclose(file);
  }
};

}  // namespace

void writePng(const std::string& path, const uint8_t* data, int width, int height, int channels) {
  if (width <= 0 || height <= 0 || (channels != 1 && channels != 3) || data == nullptr) {
    throw PngError("png '" + path + "': bad image (" + std::to_string(width) + "x" +
                   std::to_string(height) + "x" + std::to_string(channels) + ")");
  }
  PngFile f;
  f.file = std::fopen(path.c_str(), "wb");
  if (f.file == nullptr) {
    throw PngError("png '" + path + "': cannot open for writing: " + std::strerror(errno));
  }
  f.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (f.png != nullptr) f.info = png_create_info_struct(f.png);
  if (f.png == nullptr || f.info == nullptr) throw PngError("png '" + path + "': libpng init failed");
  std::vector<png_const_bytep> rows(height);
  for (int y = 0; y < height; ++y) rows[y] = data + static_cast<std::size_t>(y) * width * channels;
  // libpng reports errors by longjmp; nothing with a destructor is created past this point.
  if (setjmp(png_jmpbuf(f.png))) throw PngError("png '" + path + "': write failed");
  png_init_io(f.png, f.file);
  png_set_compression_level(f.png, 3);  // fast; these are for people, not archives
  png_set_IHDR(f.png, f.info, width, height, 8, channels == 3 ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_GRAY,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(f.png, f.info);
  png_write_rows(f.png, const_cast<png_bytepp>(rows.data()), height);
  png_write_end(f.png, nullptr);
  if (std::fflush(f.file) != 0) throw PngError("png '" + path + "': write failed");
}

namespace {

// Turbo colour map (Google, 2019), the polynomial fit by its author; x in [0, 1].
void turbo(double x, uint8_t* rgb) {
  x = std::min(1.0, std::max(0.0, x));
  const double r = 0.13572138 + x * (4.61539260 + x * (-42.66032258 + x * (132.13108234 + x * (-152.94239396 + x * 59.28637943))));
  const double g = 0.09140261 + x * (2.19418839 + x * (4.84296658 + x * (-14.18503333 + x * (4.27729857 + x * 2.82956604))));
  const double b = 0.10667330 + x * (12.64194608 + x * (-60.58204836 + x * (110.36276771 + x * (-89.90310912 + x * 27.34824973))));
  auto byte = [](double v) { return static_cast<uint8_t>(std::lround(255.0 * std::min(1.0, std::max(0.0, v)))); };
  rgb[0] = byte(r);
  rgb[1] = byte(g);
  rgb[2] = byte(b);
}

}  // namespace

void depthToColor(const float* depth, int width, int height, double min_depth, double max_depth,
                  std::vector<uint8_t>* rgb) {
  const std::size_t n = static_cast<std::size_t>(width) * height;
  rgb->assign(3 * n, 0);
  const double span = max_depth > min_depth ? max_depth - min_depth : 1.0;
  for (std::size_t i = 0; i < n; ++i) {
    const float d = depth[i];
    if (!std::isfinite(d)) continue;  // black
    turbo((d - min_depth) / span, &(*rgb)[3 * i]);
  }
}

void writeDepthPng(const std::string& path, const float* depth, int width, int height,
                   double min_depth, double max_depth) {
  std::vector<uint8_t> rgb;
  depthToColor(depth, width, height, min_depth, max_depth, &rgb);
  writePng(path, rgb.data(), width, height, 3);
}

}  // namespace tianracer_sim
