// Readback, PNG writing and offscreen targets (see framebuffer_capture.h).
#include "render/framebuffer_capture.h"

#include <glad/gl.h>

#include <algorithm>
#include <stdexcept>


namespace polarview {

RgbaImage readFramebuffer(int x, int y, int width, int height) {
  RgbaImage image;
  image.width = width;
  image.height = height;
  image.pixels.resize(size_t(width) * height * 4);
  std::vector<uint8_t> glOrder(image.pixels.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(x, y, width, height, GL_RGBA, GL_UNSIGNED_BYTE, glOrder.data());
  // GL rows run bottom to top; images top to bottom.
  const size_t rowBytes = size_t(width) * 4;
  for (int row = 0; row < height; ++row)
    std::copy_n(glOrder.data() + size_t(height - 1 - row) * rowBytes, rowBytes,
                image.pixels.data() + size_t(row) * rowBytes);
  return image;
}

// [SECTION] OffscreenTarget

OffscreenTarget::~OffscreenTarget() { destroy(); }

void OffscreenTarget::destroy() {
  if (fbo_) glDeleteFramebuffers(1, &fbo_);
  if (color_) glDeleteRenderbuffers(1, &color_);
  if (depth_) glDeleteRenderbuffers(1, &depth_);
  fbo_ = color_ = depth_ = 0;
}

namespace {

// Creates a framebuffer with a colour renderbuffer of `colorFormat` and a 24-bit depth renderbuffer;
// returns the completeness status (the objects are created either way, for the caller to delete).
GLenum createRenderbufferTarget(GLenum colorFormat, int width, int height, unsigned& fbo, unsigned& color, unsigned& depth) {
  glGenFramebuffers(1, &fbo);
  glGenRenderbuffers(1, &color);
  glGenRenderbuffers(1, &depth);
  glBindRenderbuffer(GL_RENDERBUFFER, color);
  glRenderbufferStorage(GL_RENDERBUFFER, colorFormat, width, height);
  glBindRenderbuffer(GL_RENDERBUFFER, depth);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return status;
}

}  // namespace

int maxRenderTargetSide() {
  GLint renderbuffer = 0, viewport[2] = {0, 0};
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbuffer);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  return std::max(0, std::min({renderbuffer, viewport[0], viewport[1]}));
}

std::string checkRenderTargetSize(int width, int height, int supersample) {
  if (width <= 0 || height <= 0) return "the image size must be positive";
  if (!(supersample == 1 || supersample == 2 || supersample == 4)) return "supersampling is 1, 2 or 4";
  const int limit = maxRenderTargetSide();
  const long long renderWidth = (long long)width * supersample, renderHeight = (long long)height * supersample;
  if (renderWidth <= limit && renderHeight <= limit) return {};
  std::string text = std::to_string(width) + "x" + std::to_string(height) + " at supersampling " +
                     std::to_string(supersample) + " renders " + std::to_string(renderWidth) + "x" +
                     std::to_string(renderHeight) + " pixels, over this GL's limit of " + std::to_string(limit) +
                     " per side; ";
  int fits = 0;
  for (int s : {4, 2, 1})
    if (!fits && (long long)std::max(width, height) * s <= limit) fits = s;
  if (fits) return text + "supersampling " + std::to_string(fits) + " fits";
  return text + "the largest size is " + std::to_string(limit) + " per side";
}

bool OffscreenTarget::create(int width, int height, int supersample, std::string* error) {
  destroy();
  if (std::string problem = checkRenderTargetSize(width, height, supersample); !problem.empty()) {
    if (error) *error = problem;
    return false;
  }
  width_ = width;
  height_ = height;
  supersample_ = supersample;
  const GLenum status = createRenderbufferTarget(GL_RGBA8, renderWidth(), renderHeight(), fbo_, color_, depth_);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    // Within the size limits, this is the driver running out of memory for the buffers.
    if (error)
      *error = "cannot allocate a " + std::to_string(renderWidth()) + "x" + std::to_string(renderHeight()) +
               " offscreen image (framebuffer status " + std::to_string(status) + "): try a smaller size or supersampling";
    destroy();
    return false;
  }
  return true;
}

void OffscreenTarget::bindAndClear(float r, float g, float b, float a) {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, renderWidth(), renderHeight());
  glClearColor(r, g, b, a);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

void OffscreenTarget::bindDefault() { glBindFramebuffer(GL_FRAMEBUFFER, 0); }

RgbaImage OffscreenTarget::read() const {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
  RgbaImage full = readFramebuffer(0, 0, renderWidth(), renderHeight());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  if (supersample_ == 1) return full;
  // Box filter, alpha-weighted so a transparent background does not darken silhouettes.
  RgbaImage image;
  image.width = width_;
  image.height = height_;
  image.pixels.resize(size_t(width_) * height_ * 4);
  const int s = supersample_;
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      double rgb[3] = {0, 0, 0}, alpha = 0;
      for (int dy = 0; dy < s; ++dy)
        for (int dx = 0; dx < s; ++dx) {
          const uint8_t* p = full.at(x * s + dx, y * s + dy);
          const double a = p[3] / 255.0;
          for (int c = 0; c < 3; ++c) rgb[c] += p[c] * a;
          alpha += a;
        }
      uint8_t* out = image.pixels.data() + 4 * (size_t(y) * width_ + x);
      for (int c = 0; c < 3; ++c)
        out[c] = static_cast<uint8_t>(alpha > 0 ? rgb[c] / alpha + 0.5 : 0);
      out[3] = static_cast<uint8_t>(alpha / (s * s) * 255.0 + 0.5);
    }
  return image;
}

// [SECTION] FloatTarget

FloatTarget::~FloatTarget() {
  if (fbo_) glDeleteFramebuffers(1, &fbo_);
  if (color_) glDeleteRenderbuffers(1, &color_);
  if (depth_) glDeleteRenderbuffers(1, &depth_);
}

bool FloatTarget::create(int width, int height, std::string* error) {
  width_ = width;
  height_ = height;
  const GLenum status = createRenderbufferTarget(GL_RGBA32F, width, height, fbo_, color_, depth_);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    if (error) *error = "FloatTarget: framebuffer incomplete";
    return false;
  }
  return true;
}

void FloatTarget::bindAndClear(float r, float g, float b, float a) {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, width_, height_);
  glClearColor(r, g, b, a);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

std::vector<float> FloatTarget::read() const {
  std::vector<float> pixels(size_t(width_) * height_ * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, pixels.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  return pixels;
}

}  // namespace polarview
