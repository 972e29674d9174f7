// Texture sampling: bilinear, in linear values, with glTF's wrap modes, in
// fp32 in every precision variant (the result is a colour the caller turns
// into `real3`). The includer declares `textures` (GpuTexture) and `texels`
// (uint, RGBA8; shared/shared.h says how they are laid out).
//
// Coordinates are glTF's (3.8.4.1): uv (0, 0) is the image's top-left
// corner, u grows to the right and v down, so v needs no flip against rows
// stored top first; texel (i, j) has its centre at ((i + 0.5) / w, (j + 0.5) / h).
#ifndef OCTRACE_TEXTURE_GLSL
#define OCTRACE_TEXTURE_GLSL

// The sRGB EOTF, exactly as IEC 61966-2-1 defines it (a linear segment below
// 0.04045, the 2.4 power above), per channel. Texels are decoded before they
// are blended: filtering sRGB-encoded values would darken every edge.
vec3 srgb_to_linear(vec3 c) {
  return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045)));
}

// The two texel indices (in [0, n)) either side of coordinate `x` along an
// axis of n texels, and the weight of the second: x * n - 0.5 puts texel
// centres on the integers. The coordinate is first brought into one period
// of the wrap (exact in float: x - floor(x) loses nothing), so that the
// integer indices stay small whatever uv a mesh has.
//   REPEAT:          period 1, index -1 is n - 1, index n is 0;
//   MIRRORED_REPEAT: period 2, the second half mirrored (OpenGL's
//                    mirror(): index -1 is 0, n is n - 1, 2n - 1 is 0);
//   CLAMP_TO_EDGE:   x clamped to [0, 1], indices to [0, n - 1] (which is
//                    what clamping the indices alone gives).
void wrap_axis(float x, uint n, uint wrap, out uint i0, out uint i1, out float f) {
  int size = int(n);
  if (wrap == WRAP_REPEAT) x = x - floor(x);
  else if (wrap == WRAP_MIRRORED_REPEAT) x = x - 2.0 * floor(0.5 * x);
  else x = clamp(x, 0.0, 1.0);
  float t = x * float(size) - 0.5;
  float t0 = floor(t);
  f = t - t0;
  int a = int(t0), b = a + 1;
  if (wrap == WRAP_REPEAT) {
    if (a < 0) a += size;
    if (b >= size) b -= size;
  } else if (wrap == WRAP_MIRRORED_REPEAT) {
    if (a < 0) a += 2 * size;
    if (b >= 2 * size) b -= 2 * size;
    if (a >= size) a = 2 * size - 1 - a;
    if (b >= size) b = 2 * size - 1 - b;
  } else {
    a = max(a, 0);
    b = min(b, size - 1);
  }
  // A no-op for finite coordinates; a NaN one still reads inside the texture.
  i0 = uint(clamp(a, 0, size - 1));
  i1 = uint(clamp(b, 0, size - 1));
}

// Texel (x, y)'s rgb: decoded from sRGB for a colour texture (base colour,
// emission), as stored for a data texture (metallic-roughness).
vec3 texel_rgb(GpuTexture t, uint x, uint y, bool srgb) {
  vec3 c = unpackUnorm4x8(texels[t.first_texel + y * t.width + x]).rgb;
  return srgb ? srgb_to_linear(c) : c;
}

// Texture `index` at uv, its rgb (decoded from sRGB if `srgb`) filtered bilinearly.
vec3 sample_texture(uint index, vec2 uv, bool srgb) {
  GpuTexture t = textures[index];
  uint x0, x1, y0, y1;
  float fx, fy;
  wrap_axis(uv.x, t.width, t.wrap & 0xffffu, x0, x1, fx);
  wrap_axis(uv.y, t.height, t.wrap >> 16, y0, y1, fy);
  vec3 top = mix(texel_rgb(t, x0, y0, srgb), texel_rgb(t, x1, y0, srgb), fx);
  vec3 bottom = mix(texel_rgb(t, x0, y1, srgb), texel_rgb(t, x1, y1, srgb), fx);
  return mix(top, bottom, fy);
}

// Texture `index` at uv, its alpha (linear, 0 to 1) filtered bilinearly:
// glTF's base colour alpha (3.9.6).
float sample_texture_alpha(uint index, vec2 uv) {
  GpuTexture t = textures[index];
  uint x0, x1, y0, y1;
  float fx, fy;
  wrap_axis(uv.x, t.width, t.wrap & 0xffffu, x0, x1, fx);
  wrap_axis(uv.y, t.height, t.wrap >> 16, y0, y1, fy);
  float a00 = unpackUnorm4x8(texels[t.first_texel + y0 * t.width + x0]).a;
  float a10 = unpackUnorm4x8(texels[t.first_texel + y0 * t.width + x1]).a;
  float a01 = unpackUnorm4x8(texels[t.first_texel + y1 * t.width + x0]).a;
  float a11 = unpackUnorm4x8(texels[t.first_texel + y1 * t.width + x1]).a;
  return mix(mix(a00, a10, fx), mix(a01, a11, fx), fy);
}

#endif
