// Image files for textures: PNG and JPEG (and the other formats stb_image reads), decoded by
// Debian's libstb. ROS-free.
#ifndef TIANRACER_SIM_RENDER_IMAGE_FILE_H
#define TIANRACER_SIM_RENDER_IMAGE_FILE_H

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "tianracer_sim/common/diagnostic.h"

namespace tianracer_sim {

/// An image file that is missing or cannot be decoded; the message names the file and why.
using ImageFileError = InputError;

/// 8-bit RGBA pixels, rows top to bottom (as the file stores them).
struct RgbaImage {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;  // width * height * 4

  /// The rows in the other order (bottom to top), for OpenGL's texture origin.
  std::vector<uint8_t> bottomUp() const;
};

/// Reads and decodes `path` (grey, grey+alpha, RGB and RGBA files all become RGBA). Throws
/// ImageFileError: "texture file '<path>' not found" / "... cannot be decoded (<reason>)".
RgbaImage readImageFile(const std::string& path);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_RENDER_IMAGE_FILE_H
