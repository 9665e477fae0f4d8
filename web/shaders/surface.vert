#version 300 es
// The page's surfaces are triangle meshes made on the CPU (WebGL2 has no tessellation stages):
// each vertex carries the exact position, normal, K and H of the limit surface
// (core/export/tessellation.h), relative to the model centre.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_curvature;  // (K, H)

uniform mat4 u_viewProjection;
uniform vec3 u_eye;  // relative to the model centre

out vec3 v_position;  // relative to the eye, as the desktop's SurfaceData.position
out vec3 v_normal;
out vec2 v_curvature;

void main() {
  v_position = a_position - u_eye;
  v_normal = a_normal;
  v_curvature = a_curvature;
  gl_Position = u_viewProjection * vec4(a_position, 1.0);
}
