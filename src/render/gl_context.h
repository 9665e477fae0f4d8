// HiddenGlContext: an invisible GLFW window with a GL 4.5 core context and glad loaded, for tests
// and batch rendering (needs an X server: run under xvfb-run on machines without a display).
#pragma once

#include <memory>
#include <string>

struct GLFWwindow;

namespace polarview {

class HiddenGlContext {
 public:
  // Initialises GLFW (once per process), creates a hidden w x h window with a 4.5 core context
  // (4.1 accepted), makes it current and loads glad. nullptr with a message on failure.
  static std::unique_ptr<HiddenGlContext> create(int width, int height, std::string* error);
  ~HiddenGlContext();
  HiddenGlContext(const HiddenGlContext&) = delete;
  HiddenGlContext& operator=(const HiddenGlContext&) = delete;

  // Makes the context current on the calling thread.
  void makeCurrent();
  GLFWwindow* window() const { return window_; }
  // GL_VERSION and GL_RENDERER strings.
  std::string versionString() const;

 private:
  explicit HiddenGlContext(GLFWwindow* window) : window_(window) {}
  GLFWwindow* window_ = nullptr;
};

// Loads glad's GL function pointers for the current context via glfwGetProcAddress (call once
// after glfwMakeContextCurrent in the app). False when the context lacks GL 4.1.
bool loadGlFunctions();

// The framebuffer operations the app needs besides the renderers' draws (render is the only code
// that calls GL): the current context's GL_VERSION / GL_RENDERER, ...
std::string currentGlVersion();
// ... the default framebuffer's depth at pixel (x, y) (1: nothing drawn there), ...
float readDepthAt(int x, int y);
// ... the whole framebuffer cleared to `rgb` with the depth at 1, the viewport set to it, ...
void clearFramebuffer(int width, int height, const float rgb[3]);
// ... and waiting for the GPU (frame times then include its work).
void finishGpuWork();

}  // namespace polarview
