// PNG files from RgbaImage (see image.h).
#include "pipeline/image.h"

#include <stb_image_write.h>

#include <stdexcept>

#include "core/mesh/atomic_file.h"

namespace polarview {

void writePngAtomic(const std::string& path, const RgbaImage& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != size_t(image.width) * image.height * 4)
    throw std::runtime_error("writePngAtomic: empty or inconsistent image for " + path);
  // Encode in memory, then one atomic write: no temporary of our own to name or clean up.
  std::string png;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
  };
  if (!stbi_write_png_to_func(append, &png, image.width, image.height, 4, image.pixels.data(), image.width * 4))
    throw std::runtime_error(path + ": cannot encode the PNG");
  writeFileAtomically(path, png);
}

}  // namespace polarview
