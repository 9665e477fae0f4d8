// Hidden GLFW window + glad loading (see gl_context.h).
#include "render/gl_context.h"

#include <glad/gl.h>
#include <GLFW/glfw3.h>

#include <cstdio>
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

std::string currentGlVersion() {
  const GLubyte* version = glGetString(GL_VERSION);
  const GLubyte* renderer = glGetString(GL_RENDERER);
  return std::string(version ? reinterpret_cast<const char*>(version) : "?") + " / " +
         (renderer ? reinterpret_cast<const char*>(renderer) : "?");
}

float readDepthAt(int x, int y) {
  float depth = 1.0f;
  glReadPixels(x, y, 1, 1, GL_DEPTH_COMPONENT, GL_FLOAT, &depth);
  return depth;
}

void clearFramebuffer(int width, int height, const float rgb[3]) {
  glViewport(0, 0, width, height);
  glClearColor(rgb[0], rgb[1], rgb[2], 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

void finishGpuWork() { glFinish(); }

#ifndef NDEBUG
namespace {
// Debug builds: GL errors and undefined behaviour are reported where they happen, one line each
// (KHR_debug; 4.3 core, and Mesa offers it on 4.1 too).
void APIENTRY reportGlMessage(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                              const GLchar* message, const void* user) {
  (void)source, (void)id, (void)length, (void)user;
  if (type == GL_DEBUG_TYPE_ERROR || type == GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR || severity == GL_DEBUG_SEVERITY_HIGH)
    std::fprintf(stderr, "polarview: GL: %s\n", message);
}
}  // namespace
#endif

bool loadGlFunctions() {
  const int version = gladLoadGL(glfwGetProcAddress);
  const bool enough = version != 0 && (GLAD_VERSION_MAJOR(version) > 4 ||
                                       (GLAD_VERSION_MAJOR(version) == 4 && GLAD_VERSION_MINOR(version) >= 1));
#ifndef NDEBUG
  if (enough && glDebugMessageCallback) {
    glEnable(GL_DEBUG_OUTPUT);
    glDebugMessageCallback(reportGlMessage, nullptr);
  }
#endif
  return enough;
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
