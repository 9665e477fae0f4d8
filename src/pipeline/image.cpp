// PNG files from RgbaImage (see image.h).
#include "pipeline/image.h"

#include <stb_image_write.h>

#include <stdexcept>

#include "core/mesh/atomic_file.h"

namespace polarview {
namespace {

void checkImage(const std::string& path, const RgbaImage& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != size_t(image.width) * image.height * 4)
    throw std::runtime_error("writePngAtomic: empty or inconsistent image for " + path);
}

// Encodes `pixels` (width x height, `channels` bytes each) in memory, then one atomic write: no
// temporary of our own to name or clean up.
void encodeAndWrite(const std::string& path, int width, int height, int channels, const uint8_t* pixels) {
  std::string png;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
  };
  if (!stbi_write_png_to_func(append, &png, width, height, channels, pixels, width * channels))
    throw std::runtime_error(path + ": cannot encode the PNG");
  writeFileAtomically(path, png);
}

}  // namespace

void writePngAtomic(const std::string& path, const RgbaImage& image) {
  checkImage(path, image);
  encodeAndWrite(path, image.width, image.height, 4, image.pixels.data());
}

void writeOpaquePngAtomic(const std::string& path, const RgbaImage& image) {
  checkImage(path, image);
  std::vector<uint8_t> rgb;
  rgb.reserve(image.pixels.size() / 4 * 3);
  for (size_t i = 0; i < image.pixels.size(); i += 4) rgb.insert(rgb.end(), &image.pixels[i], &image.pixels[i] + 3);
  encodeAndWrite(path, image.width, image.height, 3, rgb.data());
}

}  // namespace polarview
