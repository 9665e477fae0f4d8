// writeOpaquePngAtomic: the figure gallery's full-colour RGB PNGs, read back with stb_image.
#include <doctest/doctest.h>

#include <stb_image.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "pipeline/image.h"

namespace polarview {
namespace {

TEST_CASE("opaque png: a smooth image of 65536 colours comes back exactly as RGB, alpha dropped") {
  const std::string path = (std::filesystem::temp_directory_path() / "polarview_opaque_gradient.png").string();
  // Red along x, green along y, blue their mix: far more colours than a palette holds, so a
  // 256-colour writer (the gallery's old one) would band it. Alpha varies and must be dropped.
  RgbaImage image;
  image.width = image.height = 256;
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) image.pixels.insert(image.pixels.end(), {uint8_t(x), uint8_t(y), uint8_t((x + y) / 2), uint8_t(x ^ y)});
  writeOpaquePngAtomic(path, image);

  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  REQUIRE(bytes.size() > 26);
  CHECK(uint8_t(bytes[25]) == 2);  // IHDR colour type: RGB, no palette, no alpha
  int w = 0, h = 0, channels = 0;
  unsigned char* pixels = stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()), int(bytes.size()),
                                                &w, &h, &channels, 3);
  REQUIRE(pixels);
  CHECK(w == 256);
  CHECK(h == 256);
  CHECK(channels == 3);
  int wrong = 0;
  for (size_t i = 0; i < size_t(w) * size_t(h); ++i)
    for (int c = 0; c < 3; ++c) wrong += pixels[3 * i + size_t(c)] != image.pixels[4 * i + size_t(c)];
  CHECK(wrong == 0);
  stbi_image_free(pixels);
  std::filesystem::remove(path);
}

TEST_CASE("opaque png: an inconsistent image is refused and writes nothing") {
  const std::string path = (std::filesystem::temp_directory_path() / "polarview_opaque_bad.png").string();
  RgbaImage image;
  image.width = image.height = 4;
  image.pixels.assign(10, 0);
  CHECK_THROWS(writeOpaquePngAtomic(path, image));
  CHECK(!std::filesystem::exists(path));
}

}  // namespace
}  // namespace polarview
