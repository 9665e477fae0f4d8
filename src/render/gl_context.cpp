// Hidden GLFW window + glad loading (see gl_context.h).
#include "render/gl_context.h"

#include <glad/gl.h>
#include <GLFW/glfw3.h>

#include <string>

namespace polarview {
namespace {

// GLFW is initialised once per process and terminated at exit (windows may outlive tests).
bool ensureGlfw(std::string* error) {
  static bool initialised = false;
  if (initialised) return true;
  glfwSetErrorCallback([](int code, const char* message) {
    (void)code;
    (void)message;  // reported through the return values below
  });
  if (!glfwInit()) {
    const char* description = nullptr;
    glfwGetError(&description);
    if (error) *error = std::string("glfwInit failed (no X display? run under xvfb-run): ") +
                        (description ? description : "unknown");
    return false;
  }
  initialised = true;
  return true;
}

}  // namespace

bool loadGlFunctions() {
  const int version = gladLoadGL(glfwGetProcAddress);
  return version != 0 && (GLAD_VERSION_MAJOR(version) > 4 ||
                          (GLAD_VERSION_MAJOR(version) == 4 && GLAD_VERSION_MINOR(version) >= 1));
}

std::unique_ptr<HiddenGlContext> HiddenGlContext::create(int width, int height,
                                                         std::string* error) {
  if (!ensureGlfw(error)) return nullptr;
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(width, height, "polarview (hidden)", nullptr, nullptr);
  if (!window) {
    // Fall back to 4.1, the minimum with tessellation + the features used here.
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 1);
    window = glfwCreateWindow(width, height, "polarview (hidden)", nullptr, nullptr);
  }
  if (!window) {
    const char* description = nullptr;
    glfwGetError(&description);
    if (error) *error = std::string("cannot create a GL 4.1+ core context: ") +
                        (description ? description : "unknown");
    return nullptr;
  }
  glfwMakeContextCurrent(window);
  if (!loadGlFunctions()) {
    glfwDestroyWindow(window);
    if (error) *error = "gladLoadGL failed or GL < 4.1";
    return nullptr;
  }
  return std::unique_ptr<HiddenGlContext>(new HiddenGlContext(window));
}

HiddenGlContext::~HiddenGlContext() {
  if (window_) glfwDestroyWindow(window_);
}

void HiddenGlContext::makeCurrent() { glfwMakeContextCurrent(window_); }

std::string HiddenGlContext::versionString() const {
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return std::string(version ? version : "?") + " / " + (renderer ? renderer : "?");
}

}  // namespace polarview
