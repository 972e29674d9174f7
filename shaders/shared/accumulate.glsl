// Adding a sample to a pixel's accumulation state (shared.h: Kahan sum with
// the count in .w, compensation, M2 with the ray segments in .w), the one
// rule of path_trace.comp's whole paths and of accumulate.comp. The includer
// declares `stats` (RenderStats).
#ifndef OCTRACE_ACCUMULATE_GLSL
#define OCTRACE_ACCUMULATE_GLSL

// Adds one sample to a pixel's accumulation state. Kahan summation keeps the
// mean unbiased over millions of samples; `precise` stops the compiler from
// reassociating the compensation away. Welford's update of the sum of squared
// deviations (M2): no cancellation of two large sums, so a pixel with tiny
// variance keeps an accurate one. sq.w counts the pixel's ray segments, as the
// bits of a uint (shared.h).
void add_sample(vec3 value, uint segments, inout vec4 acc, inout vec3 comp, inout vec4 sq) {
  // A NaN or Inf sample is counted, never added: one would poison the pixel.
  if (any(isnan(value)) || any(isinf(value))) {
    atomicAdd(stats.nonfinite_samples, 1u);
    return;
  }
  precise vec3 c = comp;
  precise vec3 y = value - c;
  precise vec3 t = acc.rgb + y;
  float n = acc.w;
  vec3 mean_old = n > 0.0 ? (acc.rgb - c) / n : vec3(0.0);
  c = (t - acc.rgb) - y;
  vec3 mean_new = (t - c) / (n + 1.0);
  comp = c;
  acc = vec4(t, n + 1.0);
  sq.rgb += (value - mean_old) * (value - mean_new);
  sq.w = uintBitsToFloat(floatBitsToUint(sq.w) + segments);
}

#endif
