// PNG files of camera frames, for people (README pictures, debugging), written with libpng.
#ifndef TIANRACER_SIM_RENDER_PNG_WRITER_H
#define TIANRACER_SIM_RENDER_PNG_WRITER_H

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "tianracer_sim/common/diagnostic.h"

namespace tianracer_sim {

/// A PNG that cannot be written; the message names the path.
using PngError = InputError;

/// Writes an 8-bit image with 1 (grey) or 3 (RGB) channels, rows top to bottom. Throws
/// PngError naming the path when it cannot be written.
void writePng(const std::string& path, const uint8_t* data, int width, int height, int channels);

/// Maps a depth image (metres, NaN/inf = no data) to RGB with the turbo colour map from
/// `min_depth` (dark blue) to `max_depth` (dark red); no data is black. `rgb` is resized.
void depthToColor(const float* depth, int width, int height, double min_depth, double max_depth,
                  std::vector<uint8_t>* rgb);

/// depthToColor + writePng.
void writeDepthPng(const std::string& path, const float* depth, int width, int height,
                   double min_depth, double max_depth);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_RENDER_PNG_WRITER_H
