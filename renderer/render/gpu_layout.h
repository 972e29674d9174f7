// The C++ view of shaders/shared.h, checked against std430: sizes and offsets
// of every field. The layout-probe test checks the GLSL compiler agrees.
#pragma once

#include <cstddef>

#include "shared/shared.h"

namespace octrace::gpu {

static_assert(sizeof(GpuSphere) == 16);
static_assert(offsetof(GpuSphere, radius) == 12);

static_assert(sizeof(GpuMaterial) == 32);
static_assert(offsetof(GpuMaterial, type) == 12);
static_assert(offsetof(GpuMaterial, fuzz) == 16);
static_assert(offsetof(GpuMaterial, ior) == 20);

static_assert(sizeof(RenderStats) == 16);

static_assert(sizeof(GpuMaterialHalf) == 16);
static_assert(offsetof(GpuMaterialHalf, params) == 8);

static_assert(sizeof(GpuOctreeNode) == 32);
static_assert(offsetof(GpuOctreeNode, first) == 12);
static_assert(offsetof(GpuOctreeNode, hi) == 16);
static_assert(offsetof(GpuOctreeNode, count_or_mask) == 28);

static_assert(sizeof(FrameParams) == 128);
static_assert(offsetof(FrameParams, lens_radius) == 12);
static_assert(offsetof(FrameParams, lens_u) == 16);
static_assert(offsetof(FrameParams, width) == 28);
static_assert(offsetof(FrameParams, lens_v) == 32);
static_assert(offsetof(FrameParams, height) == 44);
static_assert(offsetof(FrameParams, pixel00) == 48);
static_assert(offsetof(FrameParams, max_depth) == 60);
static_assert(offsetof(FrameParams, pixel_du) == 64);
static_assert(offsetof(FrameParams, sample_seed) == 76);
static_assert(offsetof(FrameParams, pixel_dv) == 80);
static_assert(offsetof(FrameParams, sphere_count) == 92);
static_assert(offsetof(FrameParams, sky_a) == 96);
static_assert(offsetof(FrameParams, sky_type) == 108);
static_assert(offsetof(FrameParams, sky_b) == 112);
static_assert(offsetof(FrameParams, big_count) == 124);

static_assert(sizeof(PassConstants) == 8);

}  // namespace octrace::gpu
