// Members of the SurfaceData interface block passed TES -> (GS) -> FS. Blocks match by name, so
// each stage names its instance freely. position is relative to the model centre (world axes).
#define SURFACE_DATA_MEMBERS \
  vec3 position;             \
  vec3 normal;               \
  vec2 curvature; /* (K, H) */ \
  vec2 uv;                   \
  flat ivec2 kindRing;
