// A surface point: what the integrator knows of a hit, whatever primitive
// kind it was. Each kind's geometry file turns its hits into one; the
// shading code sees only this.
#ifndef OCTRACE_SURFACE_GLSL
#define OCTRACE_SURFACE_GLSL

struct Surface {
  vec3 p;          // the hit point
  vec3 ng;         // geometric normal, unit, outward: decides sides and offsets
  vec3 ns;         // shading normal, unit, outward (interpolated or mapped; = ng for spheres)
  uint material;   // index into the material array
  vec2 uv;         // texture coordinates (0 where a primitive has none)
  // World-space dp/du and dp/dv (unnormalised) of a triangle with uvs, for
  // normal maps (HAS_NORMAL_MAPS); 0 otherwise.
  vec3 dpdu;
  vec3 dpdv;
};

#endif
