// Images as plain pixels, and PNG files written atomically (no GL: renders and figures are read
// back into these by render/framebuffer_capture.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace polarview {

// Tightly packed RGBA8 pixels, rows top to bottom (image order, already flipped from GL).
struct RgbaImage {
  int width = 0, height = 0;
  std::vector<uint8_t> pixels;  // width * height * 4
  const uint8_t* at(int x, int y) const { return pixels.data() + 4 * (size_t(y) * width + x); }
};

// Encodes a PNG in memory (stb_image_write) and writes it atomically (core/mesh/atomic_file.h):
// readers never see a half-written file and no temporary is left. Throws std::runtime_error (an
// InputError for file errors) naming the path.
void writePngAtomic(const std::string& path, const RgbaImage& image);

// As writePngAtomic, as 8-bit RGB (alpha dropped, every colour kept): the figure gallery's PNGs,
// a quarter smaller than RGBA and free of the banding a 256-colour palette puts in smooth shading.
void writeOpaquePngAtomic(const std::string& path, const RgbaImage& image);

}  // namespace polarview
