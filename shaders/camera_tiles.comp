// The camera's tiles (RenderSettings::camera_tiles; shared/camera_tiles.glsl):
// for the pass's camera, the spheres a camera ray through each tile of
// CAMERA_TILE_PIXELS x CAMERA_TILE_PIXELS pixels can meet, which
// path_trace.comp's whole paths and head test instead of walking the tree.
// A shader of its own so that it compiles in milliseconds.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require

#include "shared/shared.h"

layout(local_size_x = WORKGROUP_SIZE * WORKGROUP_SIZE) in;

layout(std430, binding = BINDING_SCENE) readonly buffer SceneBuf { SceneParams scene; };
#include "shared/scene_buffers.glsl"
layout(push_constant) uniform Push { PassParams pass; };
#include "shared/camera_tiles.glsl"

// A subgroup a tile lists the spheres that reach into
// the tile's pyramid, for the pass's camera (PassParams), its lanes testing
// a sphere each and a ballot placing those kept (the list's order does not
// change the hit). The pyramid has its apex at the eye and its four sides
// through the tile's edges on the focus plane, a pixel outside the pixels'
// own (a camera ray's target is its pixel plus a jitter in [0, 1)): a
// sphere wholly outside one side cannot be met. With a lens
// a ray leaves from a point of the lens disc of radius R instead of the
// eye: at depth z along the view it lies within R |1 - z / f| of the
// pinhole ray to the same target (f: the focus plane's depth), so a sphere
// is kept within that much more of each side over its depths. A slack of
// 1e-5 of the sphere's distance, and of what the floats' rounding of the
// targets can move a direction, keeps a sphere that a rounded ray meets at
// a grazing angle; a NaN keeps it too. A tile stops listing at its 33rd
// sphere: its camera rays walk.
void main() {
  const uint tiles = camera_tile_total();
  const uint across = camera_tiles_across();
  const vec3 eye = pass.cam_origin;
  const vec3 du = pass.pixel_du, dv = pass.pixel_dv;
  vec3 ahead = normalize(cross(du, dv));
  float focus = dot(pass.pixel00 - eye, ahead);
  if (focus < 0.0) {
    ahead = -ahead;
    focus = -focus;
  }
  const float lens = pass.lens_radius;  // 0 for a pinhole
  // The subgroup's lanes in the workgroup (a subgroup wider than the
  // workgroup's 64 invocations has only 64).
  const uint lanes = min(gl_SubgroupSize, WORKGROUP_SIZE * WORKGROUP_SIZE);
  for (uint tile = gl_WorkGroupID.x * gl_NumSubgroups + gl_SubgroupID; tile < tiles;
       tile += gl_NumWorkGroups.x * gl_NumSubgroups) {
    const uvec2 first = uvec2(tile % across, tile / across) * CAMERA_TILE_PIXELS;
    const vec2 lo = vec2(first) - 1.0;
    const vec2 hi = vec2(min(first + CAMERA_TILE_PIXELS, uvec2(pass.width, pass.height))) + 1.0;
    const vec3 c00 = pass.pixel00 + lo.x * du + lo.y * dv - eye;
    const vec3 c11 = pass.pixel00 + hi.x * du + hi.y * dv - eye;
    const vec3 mid = 0.5 * (c00 + c11);
    // Each side holds the eye and an edge of the tile: the normal of an
    // edge along dv through the corner c00, and so on, turned into the
    // pyramid.
    vec3 side[4] = vec3[4](cross(dv, c00), cross(dv, c11), cross(du, c00), cross(du, c11));
    for (uint k = 0u; k < 4u; ++k) {
      side[k] = normalize(side[k]);
      if (dot(side[k], mid) < 0.0) side[k] = -side[k];
    }
    const float slack =
        1e-5 + 1e-6 * (length(pass.pixel00) + length(eye) + hi.x * length(du) + hi.y * length(dv)) / focus;
    const uint list = tiles + tile * CAMERA_TILE_REFS;
    uint count = 0u;
    // Every lane takes each step (a lane past the last sphere tests the
    // last again and keeps nothing), so that the ballot sees the whole
    // subgroup without relying on the lanes reconverging after a branch.
    for (uint base = 0u; base < scene.sphere_count; base += lanes) {
      const uint i = base + gl_SubgroupInvocationID;
      const GpuSphere s = sphere_at(min(i, scene.sphere_count - 1u));
      const vec3 rel = s.center - eye;
      const float r = abs(s.radius);
      const float z = dot(rel, ahead);
      const float near = max(z - r, 0.0), far = max(z + r, 0.0);
      const float spread = lens * max(abs(1.0 - near / focus), abs(1.0 - far / focus));
      const float reach = -(r + spread + length(rel) * slack);
      const bool reaches = i < scene.sphere_count && !(dot(side[0], rel) < reach || dot(side[1], rel) < reach ||
                                                       dot(side[2], rel) < reach || dot(side[3], rel) < reach);
      const uvec4 kept = subgroupBallot(reaches);
      const uint n = subgroupBallotBitCount(kept);
      if (count + n > CAMERA_TILE_REFS) {
        count = CAMERA_TILE_OVERFLOW;
        break;
      }
      if (reaches) camera_tiles[list + count + subgroupBallotExclusiveBitCount(kept)] = i;
      count += n;
    }
    if (subgroupElect()) camera_tiles[tile] = count;
  }
}
