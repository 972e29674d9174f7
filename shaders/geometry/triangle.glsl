// Triangles: watertight ray/triangle intersection and the surface at a hit,
// in fp32. The includer declares `scene`, `triangles`, `triangle_normals`
// and `triangle_uvs` (GpuInstance from shared.h) and the specialization
// constants HAS_VERTEX_NORMALS, HAS_TEXTURES and HAS_NORMAL_MAPS.
#ifndef OCTRACE_TRIANGLE_GLSL
#define OCTRACE_TRIANGLE_GLSL

#include "geometry/ray.glsl"
#include "geometry/surface.glsl"

// Per-ray constants of the watertight test (Woop, Benthin and Wald 2013,
// "Watertight Ray/Triangle Intersection", JCGT 2(1)): the ray's dominant axis
// kz becomes the z axis, kx and ky follow (swapped when dir[kz] < 0 to keep
// the winding), and a shear maps the ray onto +z. Vertices are then tested in
// 2D against the origin with edge functions that agree exactly between two
// triangles sharing an edge, so no ray slips between them.
// The permutation and the shear are kept as the rows of one matrix, so that
// a vertex's sheared coordinate is a row's products summed (`sheared`, below)
// rather than a dynamically indexed vector (which GPU compilers may move to
// local memory): with e_k the one-hot vector of component k,
//   mx = e_kx - Sx e_kz,  my = e_ky - Sy e_kz,  mz = Sz e_kz,
// each component exact (a product with 0 or 1, or -Sx itself). So A . mx
// = A[kx] + (-Sx A[kz]) + 0 rounds once, after the one product: the value
// of the paper's A[kx] - Sx A[kz] (up to the sign of a zero, which no test
// below tells apart), in 5 operations where the one-hot form took 7 and the
// z coordinate besides (optimisation log 72).
struct RayShear {
  vec3 mx, my, mz;
};

RayShear ray_shear(vec3 dir) {
  vec3 a = abs(dir);
  int kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
  int kx = kz == 2 ? 0 : kz + 1;
  int ky = kx == 2 ? 0 : kx + 1;
  if (dir[kz] < 0.0) {
    int t = kx;
    kx = ky;
    ky = t;
  }
  vec3 ex = vec3(kx == 0, kx == 1, kx == 2), ey = vec3(ky == 0, ky == 1, ky == 2), ez = vec3(kz == 0, kz == 1, kz == 2);
  float dz = dot(dir, ez);
  float sx = dot(dir, ex) / dz, sy = dot(dir, ey) / dz, sz = 1.0 / dz;
  return RayShear(ex - sx * ez, ey - sy * ez, sz * ez);
}

// One sheared coordinate of a vertex (relative to the ray's origin), row m
// of the shear: three products, each rounded on its own, and two sums.
// Written out rather than as dot(), whose rounding SPIR-V leaves to the
// driver: NVIDIA's fuses it (one rounding of A[kx] - Sx A[kz] instead of
// two), which changed the images and would leave watertightness to how the
// compiler treats each vertex (optimisation log 72).
float sheared(vec3 a, vec3 m) {
  precise float r = a.x * m.x + a.y * m.y + a.z * m.z;
  return r;
}

// The edge functions U, V, W (unnormalised barycentrics of v0, v1, v2) and
// the scaled distance T of the ray against triangle (v0, v1, v2); det = U+V+W.
// Returns false when the ray misses the triangle's inside (an edge or vertex
// counts as inside: a ray through a shared edge hits both triangles at the
// same t, and the tie goes to the lower id) or the triangle has no area.
// The z coordinates (Sz A[kz], ...) are needed for T alone, so a miss never
// works them out.
bool triangle_edges(vec3 origin, RayShear sh, vec3 v0, vec3 v1, vec3 v2, out vec3 uvw, out float T, out float det) {
  // `precise`: no fused multiply-add. The test is exact only if every
  // product is rounded on its own: with Cx*By - Cy*Bx fused, a triangle whose
  // three vertices coincide got U = V = W = the same rounding residue, a
  // non-zero det and a hit (seen on the H100, not on lavapipe), and two
  // triangles sharing an edge could round their edge functions differently.
  precise vec3 A = v0 - origin, B = v1 - origin, C = v2 - origin;
  precise float Ax = sheared(A, sh.mx), Ay = sheared(A, sh.my);
  precise float Bx = sheared(B, sh.mx), By = sheared(B, sh.my);
  precise float Cx = sheared(C, sh.mx), Cy = sheared(C, sh.my);
  precise float U = Cx * By - Cy * Bx;
  precise float V = Ax * Cy - Ay * Cx;
  precise float W = Bx * Ay - By * Ax;
  if ((U < 0.0 || V < 0.0 || W < 0.0) && (U > 0.0 || V > 0.0 || W > 0.0)) return false;
  det = U + V + W;  // exactly 0 for a repeated vertex (U = -V) or a point
  if (det == 0.0) return false;  // zero area (or seen exactly edge-on): never hit
  precise float Az = sheared(A, sh.mz), Bz = sheared(B, sh.mz), Cz = sheared(C, sh.mz);
  T = U * Az + V * Bz + W * Cz;
  uvw = vec3(U, V, W);
  return true;
}

// Object-space normal n of instance g in world space: the transpose of the
// world-to-object 3x3 (the inverse transpose of the placement), unnormalised.
vec3 normal_to_world(GpuInstance g, vec3 n) {
  return n.x * g.to_object0.xyz + n.y * g.to_object1.xyz + n.z * g.to_object2.xyz;
}

// The tangent frame of a normal map: dp/du and dp/dv of the triangle (the
// directions in which u and v grow, constant over a triangle: the usual
// per-triangle tangents, Lengyel 2001, "Computing Tangent Space Basis
// Vectors for an Arbitrary Mesh"), in object space and then in world space
// through the placement (tangents are directions, so the inverse of the
// world-to-object 3x3, not its transpose; a mirror keeps its handedness).
// A triangle whose uvs have no area gets none (0): the caller keeps the
// unmapped normal.
void triangle_tangents(GpuTriangle tri, GpuTriangleUvs u, GpuInstance g, out vec3 dpdu, out vec3 dpdv) {
  vec3 e1 = tri.v1 - tri.v0, e2 = tri.v2 - tri.v0;
  vec2 d1 = u.uv1 - u.uv0, d2 = u.uv2 - u.uv0;
  float r = d1.x * d2.y - d2.x * d1.y;
  dpdu = dpdv = vec3(0.0);
  if (r == 0.0) return;
  mat3 to_world = inverse(transpose(mat3(g.to_object0.xyz, g.to_object1.xyz, g.to_object2.xyz)));
  dpdu = to_world * ((e1 * d2.y - e2 * d1.y) / r);
  dpdv = to_world * ((e2 * d1.x - e1 * d2.x) / r);
}

// A tangent of the file (GpuTriangleNormals.tangentK, shared.h): the unit
// vector of its octahedral encoding (Cigolle et al. 2014, listing 2), and
// its handedness w.
vec4 unpack_tangent(uint bits) {
  vec2 p = vec2(bits & TANGENT_UNORM_MAX, (bits >> 15) & TANGENT_UNORM_MAX) * (2.0 / float(TANGENT_UNORM_MAX)) - 1.0;
  vec3 v = vec3(p, 1.0 - abs(p.x) - abs(p.y));
  if (v.z < 0.0) v.xy = (1.0 - abs(v.yx)) * vec2(p.x >= 0.0 ? 1.0 : -1.0, p.y >= 0.0 ? 1.0 : -1.0);
  return vec4(normalize(v), (bits & TANGENT_NEGATIVE_W) != 0u ? -1.0 : 1.0);
}

// The normal map's frame from the file's tangents (glTF 3.7.2.1), where all
// three vertices have one: the tangent and the handedness interpolated at
// the barycentrics b, bitangent = cross(normal, tangent) * w in object space
// (`normal` the interpolated object-space vertex normal), both into world
// space through the placement as triangle_tangents' are. dpdv is the
// bitangent negated: mapped_normal (shading/materials.glsl) turns its
// bitangent away from dp/dv, whose direction of growing v is the image's
// "down". False (the uvs' frame is used) where a vertex has none.
bool file_tangents(GpuTriangleNormals n, vec3 b, vec3 normal, GpuInstance g, out vec3 dpdu, out vec3 dpdv) {
  dpdu = dpdv = vec3(0.0);
  if ((n.tangent0 & n.tangent1 & n.tangent2 & TANGENT_PRESENT) == 0u) return false;
  vec4 t = b.x * unpack_tangent(n.tangent0) + b.y * unpack_tangent(n.tangent1) + b.z * unpack_tangent(n.tangent2);
  mat3 to_world = inverse(transpose(mat3(g.to_object0.xyz, g.to_object1.xyz, g.to_object2.xyz)));
  dpdu = to_world * t.xyz;
  dpdv = -(to_world * (t.w < 0.0 ? -cross(normal, t.xyz) : cross(normal, t.xyz)));
  return true;
}

// The surface of triangle `i` (of instance g) at distance t; `oray` is the
// ray in the instance's object space. The geometric normal follows the
// winding (counter-clockwise = front, outward for a closed mesh; the inverse
// transpose keeps a mirrored instance's outside outside); with vertex normals
// the shading normal, and with textures the texture coordinates, interpolate
// the vertices' at the hit's barycentrics (worked out again here, once per
// hit, rather than carried through the traversal).
Surface triangle_surface(Ray ray, Ray oray, float t, uint i, GpuInstance g) {
  GpuTriangle tri = triangle_at(i);
  vec3 p = ray.origin + t * ray.dir;
  vec3 ng = safe_normalize(normal_to_world(g, cross(tri.v1 - tri.v0, tri.v2 - tri.v0)), -ray.dir);
  vec3 ns = ng;
  vec2 uv = vec2(0.0);
  vec3 dpdu = vec3(0.0), dpdv = vec3(0.0);
  // The general pipeline reads normals and uvs only where the scene uploaded them.
  bool smooth_normals = HAS_VERTEX_NORMALS && scene.vertex_normals != 0u;
  bool textured = HAS_TEXTURES && scene.triangle_uvs != 0u;
  if (smooth_normals || textured) {
    vec3 uvw;
    float T, det;
    if (triangle_edges(oray.origin, ray_shear(oray.dir), tri.v0, tri.v1, tri.v2, uvw, T, det)) {
      vec3 b = uvw / det;
      bool from_file = false;
      if (smooth_normals) {
        GpuTriangleNormals n = triangle_normals_at(i);
        vec3 normal = b.x * n.n0 + b.y * n.n1 + b.z * n.n2;
        ns = safe_normalize(normal_to_world(g, normal), ng);
        if (HAS_NORMAL_MAPS && textured) from_file = file_tangents(n, b, normal, g, dpdu, dpdv);
      }
      if (textured) {
        GpuTriangleUvs u = triangle_uvs_at(i);
        uv = b.x * u.uv0 + b.y * u.uv1 + b.z * u.uv2;
        if (HAS_NORMAL_MAPS && !from_file) triangle_tangents(tri, u, g, dpdu, dpdv);
      }
    }
  }
  return Surface(p, ng, ns, tri.material, uv, dpdu, dpdv);
}

#endif
