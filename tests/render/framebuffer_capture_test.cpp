// Capture: PNG files (size, validity, atomic write), supersampled and transparent offscreen targets.
#include <doctest/doctest.h>

#include <glad/gl.h>
#include <stb_image.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "render_test_support.h"

namespace polarview {
namespace {

namespace fs = std::filesystem;

fs::path scratchPng(const std::string& name) {
  return fs::temp_directory_path() / ("polarview_capture_" + std::to_string(::getpid()) + "_" + name);
}

// Width and height from a PNG's IHDR chunk (big endian), after checking the signature.
bool pngHeaderSize(const fs::path& path, int* width, int* height) {
  std::ifstream in(path, std::ios::binary);
  unsigned char header[24] = {};
  in.read(reinterpret_cast<char*>(header), 24);
  const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (!in || !std::equal(signature, signature + 8, header) || std::string(header + 12, header + 16) != "IHDR")
    return false;
  auto be32 = [&](int at) {
    return int(header[at]) << 24 | int(header[at + 1]) << 16 | int(header[at + 2]) << 8 | int(header[at + 3]);
  };
  *width = be32(16);
  *height = be32(20);
  return true;
}

TEST_CASE("capture: a rendered PNG has the requested size and decodes to the same pixels") {
  test::glContext();
  auto renderer = test::makeRenderer();
  renderer->setPatches(test::paraboloidCap(8, 1.0, 1.0));
  for (const auto& [w, h, supersample] : {std::tuple{64, 48, 1}, std::tuple{37, 53, 2},
                                          std::tuple{80, 20, 4}}) {
    CAPTURE(w);
    CAPTURE(h);
    CAPTURE(supersample);
    OffscreenTarget target;
    std::string error;
    REQUIRE_MESSAGE(target.create(w, h, supersample, &error), error);
    target.bindAndClear(0.2f, 0.3f, 0.4f, 0.0f);  // transparent background
    ViewParams view = test::topView(Point(0.0), 1.2, {0, 0, target.renderWidth(), target.renderHeight()});
    renderer->draw(view, ShadingParams{}, test::surfaceOnly());
    const RgbaImage image = target.read();
    OffscreenTarget::bindDefault();
    REQUIRE(image.width == w);
    REQUIRE(image.height == h);
    // Background corners are transparent, the surface in the middle opaque.
    CHECK(image.at(0, 0)[3] == 0);
    CHECK(image.at(w - 1, h - 1)[3] == 0);
    CHECK(image.at(w / 2, h / 2)[3] == 255);

    const fs::path path = scratchPng("size.png");
    writePngAtomic(path.string(), image);
    int headerW = 0, headerH = 0;
    CHECK(pngHeaderSize(path, &headerW, &headerH));
    CHECK(headerW == w);
    CHECK(headerH == h);
    int dw = 0, dh = 0, channels = 0;
    unsigned char* decoded = stbi_load(path.string().c_str(), &dw, &dh, &channels, 4);
    REQUIRE(decoded != nullptr);
    CHECK(std::equal(image.pixels.begin(), image.pixels.end(), decoded));
    stbi_image_free(decoded);
    CHECK_FALSE(fs::exists(path.string() + ".tmp"));
    fs::remove(path);
  }
}

TEST_CASE("capture: rows are flipped so the image's top row is the framebuffer's top") {
  test::glContext();
  OffscreenTarget target;
  std::string error;
  REQUIRE(target.create(8, 6, 1, &error));
  target.bindAndClear(0, 0, 1, 1);
  // Paint the bottom two GL rows red with a scissored clear.
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, 0, 8, 2);
  glClearColor(1, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
  const RgbaImage image = target.read();
  OffscreenTarget::bindDefault();
  for (int x = 0; x < 8; ++x) {
    CHECK(image.at(x, 0)[2] == 255);  // top: blue
    CHECK(image.at(x, 5)[0] == 255);  // bottom: red
    CHECK(image.at(x, 4)[0] == 255);
    CHECK(image.at(x, 3)[0] == 0);
  }
}

TEST_CASE("capture: writePngAtomic throws for an unwritable path or an empty image") {
  RgbaImage image;
  image.width = 2;
  image.height = 2;
  image.pixels.assign(16, 128);
  CHECK_THROWS_WITH(writePngAtomic("/nonexistent-dir/x.png", image), doctest::Contains("/nonexistent-dir/x.png"));
  RgbaImage empty;
  CHECK_THROWS(writePngAtomic(scratchPng("empty.png").string(), empty));
  CHECK_FALSE(fs::exists(scratchPng("empty.png")));
}

}  // namespace
}  // namespace polarview
