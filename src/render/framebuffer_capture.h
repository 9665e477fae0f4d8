// Framebuffer capture: read pixels back (into pipeline/image.h's RgbaImage), and an offscreen render target
// (FBO with optional supersampling and a transparent background) for screenshots and tests.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "pipeline/image.h"

namespace polarview {

// Reads (x, y, width, height) of the currently bound read framebuffer (bottom-left origin, as GL)
// into an image with rows top to bottom. Needs a current GL context.
RgbaImage readFramebuffer(int x, int y, int width, int height);

// The largest side of an offscreen target this GL allows (GL_MAX_RENDERBUFFER_SIZE and the viewport
// limit). Needs a current GL context.
int maxRenderTargetSide();
// Empty when a width x height image at `supersample` (1, 2 or 4) fits this GL, else one sentence
// saying what does, e.g. "8192x8192 at supersampling 4 renders 32768x32768 pixels, over this GL's
// limit of 16384 per side; supersampling 2 fits". Needs a current GL context.
std::string checkRenderTargetSize(int width, int height, int supersample);

// An offscreen colour + depth target of width x height output pixels, rendered at `supersample`
// times the size (1, 2 or 4) and box-filtered down on read. Needs a current GL context.
class OffscreenTarget {
 public:
  OffscreenTarget() = default;
  ~OffscreenTarget();
  OffscreenTarget(const OffscreenTarget&) = delete;
  OffscreenTarget& operator=(const OffscreenTarget&) = delete;

  // Creates (or re-creates) the FBO; false with a message when the FBO is incomplete.
  bool create(int width, int height, int supersample, std::string* error);
  // Binds the FBO, sets the full viewport and clears to `clear` (alpha 0 gives a transparent
  // background in the PNG).
  void bindAndClear(float r, float g, float b, float a);
  // Render size (width * supersample): pass these to ViewParams::viewport.
  int renderWidth() const { return width_ * supersample_; }
  int renderHeight() const { return height_ * supersample_; }
  int supersample() const { return supersample_; }
  // Reads the FBO and box-filters it to width x height (straight alpha, rows top to bottom).
  RgbaImage read() const;
  // Binds the default framebuffer again.
  static void bindDefault();

 private:
  void destroy();
  unsigned fbo_ = 0, color_ = 0, depth_ = 0;
  int width_ = 0, height_ = 0, supersample_ = 1;
};

// Float target for probes and tests: RGBA32F colour + depth, readback as floats.
class FloatTarget {
 public:
  FloatTarget() = default;
  ~FloatTarget();
  FloatTarget(const FloatTarget&) = delete;
  FloatTarget& operator=(const FloatTarget&) = delete;
  bool create(int width, int height, std::string* error);
  void bindAndClear(float r, float g, float b, float a);
  // width * height * 4 floats, rows bottom to top (GL order).
  std::vector<float> read() const;

 private:
  unsigned fbo_ = 0, color_ = 0, depth_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace polarview
