// Members of the SurfaceData interface block passed TES -> (GS) -> FS. Blocks match by name, so
// each stage names its instance freely. position is relative to the eye (world axes, see
// patch_frame.glsl), so it keeps float precision in close-ups.
#define SURFACE_DATA_MEMBERS \
  vec3 position;             \
  vec3 normal;               \
  vec2 curvature; /* (K, H) */ \
  vec2 uv;                   \
  flat ivec2 kindRing;
