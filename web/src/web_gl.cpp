#include "web_gl.h"

#include <GLES3/gl3.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <glm/gtc/type_ptr.hpp>

namespace polarview {

namespace {

constexpr float kBackground[3] = {0.17f, 0.18f, 0.20f};  // the desktop's (app/viewer_app.h)

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read shader " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string resolveIncludes(const std::string& path, int depth) {
  if (depth > 8) throw std::runtime_error("shader includes nest too deep at " + path);
  std::istringstream in(readText(path));
  std::string line, out;
  for (int number = 1; std::getline(in, line); ++number) {
    const size_t at = line.find("#include \"");
    if (at != std::string::npos && line.find_first_not_of(" \t") == at) {
      const size_t end = line.find('"', at + 10);
      out += resolveIncludes("/shaders/" + line.substr(at + 10, end - at - 10), depth + 1);
    } else {
      out += line + '\n';
    }
  }
  return out;
}

unsigned compile(unsigned type, const std::string& source, const std::string& name) {
  const unsigned shader = glCreateShader(type);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw std::runtime_error(name + ": " + log);
  }
  return shader;
}

void setUniform(unsigned program, const char* name, float v) { glUniform1f(glGetUniformLocation(program, name), v); }
void setUniform(unsigned program, const char* name, int v) { glUniform1i(glGetUniformLocation(program, name), v); }
void setUniform(unsigned program, const char* name, const glm::vec3& v) {
  glUniform3fv(glGetUniformLocation(program, name), 1, glm::value_ptr(v));
}

float floatInRange(double value) {
  constexpr double kMax = std::numeric_limits<float>::max();
  return std::isnan(value) ? 0.0f : float(std::clamp(value, -kMax, kMax));
}

}  // namespace

std::string loadShaderSource(const std::string& path, const std::string& defines) {
  std::string text = resolveIncludes(path, 0);
  const size_t versionEnd = text.find('\n');
  return text.substr(0, versionEnd + 1) + "precision highp float;\nprecision highp int;\n" + defines +
         text.substr(versionEnd + 1);
}

WebRenderer::~WebRenderer() {
  for (Buffers& b : buffers_) {
    glDeleteVertexArrays(1, &b.vao);
    glDeleteBuffers(1, &b.vbo);
    glDeleteBuffers(1, &b.ibo);
  }
  for (unsigned program : programs_) glDeleteProgram(program);
}

bool WebRenderer::init(std::string* error) {
  try {
    const std::string vertex = loadShaderSource("/shaders/surface.vert", "");
    for (size_t mode = 0; mode < programs_.size(); ++mode) {
      const std::string define = "#define SHADING_MODE " + std::to_string(mode) + "\n";
      const unsigned vs = compile(GL_VERTEX_SHADER, vertex, "surface.vert");
      const unsigned fs = compile(GL_FRAGMENT_SHADER, loadShaderSource("/shaders/surface.frag", define), "surface.frag");
      const unsigned program = glCreateProgram();
      glAttachShader(program, vs);
      glAttachShader(program, fs);
      glLinkProgram(program);
      glDeleteShader(vs);
      glDeleteShader(fs);
      GLint ok = 0;
      glGetProgramiv(program, GL_LINK_STATUS, &ok);
      if (!ok) {
        char log[4096] = {};
        glGetProgramInfoLog(program, sizeof log, nullptr, log);
        throw std::runtime_error(std::string("surface program: ") + log);
      }
      programs_[mode] = program;
    }
  } catch (const std::exception& e) {
    if (error) *error = e.what();
    return false;
  }
  return true;
}

void WebRenderer::upload(const WebScene& scene) {
  if (scene.revision() == uploaded_) return;
  uploaded_ = scene.revision();
  const std::vector<ViewMesh>& views = scene.views();
  while (buffers_.size() < views.size()) {
    Buffers b;
    glGenVertexArrays(1, &b.vao);
    glGenBuffers(1, &b.vbo);
    glGenBuffers(1, &b.ibo);
    glBindVertexArray(b.vao);
    glBindBuffer(GL_ARRAY_BUFFER, b.vbo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, b.ibo);
    const GLsizei stride = kWebVertexFloats * sizeof(float);
    glEnableVertexAttribArray(0);  // a_position
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
    glEnableVertexAttribArray(1);  // a_normal
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(3 * sizeof(float)));
    glEnableVertexAttribArray(2);  // a_curvature (K, H)
    glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(6 * sizeof(float)));
    glBindVertexArray(0);
    buffers_.push_back(b);
  }
  for (size_t v = 0; v < buffers_.size(); ++v) {
    Buffers& b = buffers_[v];
    b.indexCount = 0;
    if (v >= views.size() || views[v].indices.empty()) continue;
    glBindVertexArray(b.vao);
    glBindBuffer(GL_ARRAY_BUFFER, b.vbo);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(views[v].vertices.size() * sizeof(float)), views[v].vertices.data(), GL_STATIC_DRAW);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(views[v].indices.size() * sizeof(uint32_t)), views[v].indices.data(),
                 GL_STATIC_DRAW);
    b.indexCount = int(views[v].indices.size());
    glBindVertexArray(0);
  }
}

void WebRenderer::clear(int width, int height) {
  glDisable(GL_SCISSOR_TEST);
  glViewport(0, 0, width, height);
  glClearColor(kBackground[0], kBackground[1], kBackground[2], 1.0f);
  glClearDepthf(1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

void WebRenderer::drawView(size_t view, const WebDraw& draw) {
  if (view >= buffers_.size() || buffers_[view].indexCount == 0) return;
  const ShadingParams& shading = draw.shading;
  const unsigned program = programs_[size_t(shading.mode)];
  glViewport(draw.viewport.x, draw.viewport.y, draw.viewport.z, draw.viewport.w);
  glEnable(GL_SCISSOR_TEST);
  glScissor(draw.viewport.x, draw.viewport.y, draw.viewport.z, draw.viewport.w);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);  // open surfaces are seen from both sides
  glDisable(GL_BLEND);
  glUseProgram(program);
  glUniformMatrix4fv(glGetUniformLocation(program, "u_viewProjection"), 1, GL_FALSE, glm::value_ptr(draw.viewProjection));

  // The desktop's uniforms (render/patch_renderer.cpp setShadingUniforms), relative to the centre.
  const glm::vec3 B = glm::normalize(shading.highlightDir);
  const glm::vec3 W = perpendicularTo(B, shading.highlightPlaneNormal);
  const glm::vec3 E = glm::cross(W, B);
  const glm::vec3 keyView = glm::length(shading.keyLightView) > 1e-6f ? glm::normalize(shading.keyLightView) : glm::vec3(0, 0, 1);
  const glm::vec3 keyWorld = glm::normalize(glm::transpose(draw.viewRotation) * keyView);
  setUniform(program, "u_colormap", int(shading.colormap));
  // The range in the vertices' curvature units (render/patch_renderer.cpp does the same).
  const double unit = shading.mode == ShadingParams::Mode::Gaussian ? draw.curvatureUnit * draw.curvatureUnit : draw.curvatureUnit;
  setUniform(program, "u_rangeLow", floatInRange(shading.range.low * unit));
  setUniform(program, "u_rangeHigh", floatInRange(shading.range.high * unit));
  setUniform(program, "u_curvatureLighting", shading.curvatureLighting);
  setUniform(program, "u_eye", draw.eye);
  setUniform(program, "u_keyLight", keyWorld);
  setUniform(program, "u_surfaceColor", shading.surfaceColor);
  setUniform(program, "u_lineDirection", B);
  setUniform(program, "u_lineAcross", E);
  setUniform(program, "u_planeNormal", W);
  setUniform(program, "u_planePoint", W * (2.0f * draw.radius));
  setUniform(program, "u_lineSpacing", shading.mode == ShadingParams::Mode::Reflection
                                           ? std::max(shading.reflectionSpacing, 1e-4f)
                                           : std::max(shading.highlightSpacing * draw.radius, 1e-12f));
  setUniform(program, "u_lineWidth", std::clamp(shading.highlightWidth, 0.0f, 1.0f));

  glBindVertexArray(buffers_[view].vao);
  glDrawElements(GL_TRIANGLES, buffers_[view].indexCount, GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_DEPTH_TEST);
}

}  // namespace polarview
