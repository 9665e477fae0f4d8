// writeIndexedPngAtomic: the 256-colour PNGs of the figure gallery, read back with stb_image.
#include <doctest/doctest.h>

#include <stb_image.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "pipeline/indexed_png.h"

namespace polarview {
namespace {

RgbaImage readBack(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  REQUIRE(bytes.size() > 8);
  CHECK(uint8_t(bytes[25]) == 3);  // IHDR colour type: indexed
  int w = 0, h = 0, channels = 0;
  unsigned char* pixels = stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()), int(bytes.size()),
                                                &w, &h, &channels, 4);
  REQUIRE(pixels);
  RgbaImage image;
  image.width = w;
  image.height = h;
  image.pixels.assign(pixels, pixels + size_t(w) * size_t(h) * 4);
  stbi_image_free(pixels);
  return image;
}

RgbaImage makeImage(int w, int h, uint8_t (*colour)(int x, int y, int c)) {
  RgbaImage image;
  image.width = w;
  image.height = h;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < 3; ++c) image.pixels.push_back(colour(x, y, c));
      image.pixels.push_back(255);
    }
  return image;
}

TEST_CASE("indexed png: an image of at most 256 colours comes back exactly") {
  const std::string path = (std::filesystem::temp_directory_path() / "polarview_indexed_exact.png").string();
  // 16 x 16 distinct colours in blocks.
  const RgbaImage image = makeImage(64, 48, [](int x, int y, int c) {
    return uint8_t(c == 0 ? (x / 4) * 17 : c == 1 ? (y / 3) * 17 : 99);
  });
  writeIndexedPngAtomic(path, image);
  const RgbaImage back = readBack(path);
  REQUIRE(back.width == image.width);
  REQUIRE(back.height == image.height);
  CHECK(back.pixels == image.pixels);
  std::filesystem::remove(path);
}

TEST_CASE("indexed png: a smooth image of many colours stays within a few levels of each pixel") {
  const std::string path = (std::filesystem::temp_directory_path() / "polarview_indexed_gradient.png").string();
  // 65536 colours: red along x, green along y, blue their mix.
  const RgbaImage image = makeImage(256, 256, [](int x, int y, int c) {
    return uint8_t(c == 0 ? x : c == 1 ? y : (x + y) / 2);
  });
  writeIndexedPngAtomic(path, image);
  const RgbaImage back = readBack(path);
  REQUIRE(back.pixels.size() == image.pixels.size());
  int worst = 0;
  double sum = 0;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const int d = std::abs(int(back.pixels[i]) - int(image.pixels[i]));
    worst = std::max(worst, d);
    sum += d;
  }
  // 256 boxes over a 256 x 256 colour plane: boxes of about 16 x 16 levels.
  CHECK(worst <= 16);
  CHECK(sum / double(image.pixels.size()) < 4.0);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace polarview
