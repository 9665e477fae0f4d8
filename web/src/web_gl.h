// The page's one WebGL2 file: the surface programs (web/shaders, with the desktop's
// shaders/common colour maps and lighting), the views' vertex buffers, and drawing one view.
// Nothing else in web/ calls GL except Dear ImGui's OpenGL3 backend.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "pipeline/shading.h"
#include "web_scene.h"

namespace polarview {

// What one view's draw needs, in coordinates relative to the model centre.
struct WebDraw {
  glm::mat4 viewProjection{1.0f};
  glm::mat3 viewRotation{1.0f};  // world -> view axes (the key light is fixed in view space)
  glm::vec3 eye{0.0f};
  glm::ivec4 viewport{0, 0, 1, 1};  // framebuffer pixels, bottom-left origin
  float radius = 1.0f;              // model bounding radius in units of curvatureUnit (light lines)
  double curvatureUnit = 1.0;       // WebScene::unit(): the vertices' K and H are K * unit^2, H * unit
  ShadingParams shading;
};

class WebRenderer {
 public:
  ~WebRenderer();
  // Compiles one program per shading mode from /shaders (embedded in the wasm); false with the log.
  bool init(std::string* error);
  // Copies the scene's meshes to the GPU when its revision changed. [O(vertices)]
  void upload(const WebScene& scene);
  // Clears the whole canvas to the desktop viewer's background.
  void clear(int width, int height);
  // Draws the surface of view `view` into draw.viewport (scissored). [O(triangles)]
  void drawView(size_t view, const WebDraw& draw);

 private:
  struct Buffers {
    unsigned vao = 0, vbo = 0, ibo = 0;
    int indexCount = 0;
  };
  std::array<unsigned, 5> programs_{};  // by ShadingParams::Mode
  std::vector<Buffers> buffers_;
  uint64_t uploaded_ = ~uint64_t(0);
};

// GLSL text of `path` with its #include "x" lines replaced by /shaders/x, recursively; `defines`
// go after the #version line with the ES precision statements. Throws std::runtime_error naming
// a file it cannot read. [O(text)]
std::string loadShaderSource(const std::string& path, const std::string& defines);

}  // namespace polarview
