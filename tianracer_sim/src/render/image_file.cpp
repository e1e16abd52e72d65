#include "tianracer_sim/render/image_file.h"

#include <sys/stat.h>

#include <cstring>

#include <stb/stb_image.h>

namespace tianracer_sim {

std::vector<uint8_t> RgbaImage::bottomUp() const {
  std::vector<uint8_t> out(rgba.size());
  const std::size_t row = static_cast<std::size_t>(width) * 4;
  for (int y = 0; y < height; ++y) {
    std::memcpy(&out[(height - 1 - y) * row], &rgba[y * row], row);
  }
  return out;
}

RgbaImage readImageFile(const std::string& path) {
  struct stat st {};
  if (path.empty() || ::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) {
    throw ImageFileError("texture file '" + path + "' not found");
  }
  int w = 0, h = 0, channels = 0;
  // stb_image keeps its failure reason in a global: the renderer calls this under the GL
  // lock, one file at a time.
  stbi_uc* pixels = stbi_load(path.c_str(), &w, &h, &channels, 4);
  if (pixels == nullptr) {
    const char* why = stbi_failure_reason();
    throw ImageFileError("texture file '" + path + "' cannot be decoded (" +
                         (why ? why : "unknown reason") + ")");
  }
  RgbaImage image;
  image.width = w;
  image.height = h;
  image.rgba.assign(pixels, pixels + static_cast<std::size_t>(w) * h * 4);
  stbi_image_free(pixels);
  return image;
}

}  // namespace tianracer_sim
