// The scene's big per-primitive arrays (spheres, their material indices,
// materials (the rtiow field has one per sphere), triangles with their
// normals and uvs, octree nodes and references) and the one way the shaders
// read them: sphere_at(i), sphere_material_at(i), material_at(i),
// triangle_at(i), triangle_normals_at(i), triangle_uvs_at(i), node_at(i),
// ref_at(i).
//
// A scene whose arrays each fit one storage buffer reads them from the
// descriptors BINDING_SPHERES etc., as it always has. A larger one (render/
// gpu_scene.cpp decides) is rendered by the split pipeline, compiled with
// OCTRACE_SPLIT=1: every array is cut into parts of at most 2^PART_LOG2 bytes
// (PART_LOG2 <= log2 of the device's maxStorageBufferRange), each its own
// buffer, read through its buffer device address (GL_EXT_buffer_reference;
// VK_KHR_buffer_device_address, core in Vulkan 1.2; descriptor arrays of
// buffers were not an option: lavapipe allows 32 storage buffers per stage).
// An array of elements of s bytes holds 2^(PART_LOG2 - ceil(log2 s))
// elements per part (a power of two, so the part is a shift and the index in
// it a mask): element i is in part i >> shift at i & (2^shift - 1). The
// part table (shared.h, BINDING_BUFFER_PARTS) holds the parts' addresses.
#ifndef OCTRACE_SCENE_BUFFERS_GLSL
#define OCTRACE_SCENE_BUFFERS_GLSL

// The material as the precision variant reads it (shared.h).
#if OCTRACE_PRECISION >= 1
#define OCTRACE_MATERIAL GpuMaterialHalf
#else
#define OCTRACE_MATERIAL GpuMaterial
#endif

#if OCTRACE_SPLIT
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

layout(constant_id = SPEC_PART_LOG2) const uint PART_LOG2 = 27u;
layout(std430, binding = BINDING_BUFFER_PARTS) readonly buffer PartBuf { uvec2 part_address[]; };

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer SpherePart { GpuSphere v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer UintPart { uint v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer TrianglePart { GpuTriangle v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer TriangleNormalPart { GpuTriangleNormals v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer TriangleUvPart { GpuTriangleUvs v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer NodePart { GpuOctreeNode v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer MaterialPart { OCTRACE_MATERIAL v[]; };

// The address of the part of `array` (SPLIT_*) that holds element i, and i's
// index in it, for elements of 2^size_log2 bytes or fewer.
#define OCTRACE_PART(array, size_log2, i) part_address[(array) * MAX_PARTS + ((i) >> (PART_LOG2 - (size_log2)))]
#define OCTRACE_IN_PART(size_log2, i) ((i) & ((1u << (PART_LOG2 - (size_log2))) - 1u))

GpuSphere sphere_at(uint i) { return SpherePart(OCTRACE_PART(SPLIT_SPHERES, 4u, i)).v[OCTRACE_IN_PART(4u, i)]; }
uint sphere_material_at(uint i) {
  return UintPart(OCTRACE_PART(SPLIT_SPHERE_MATERIALS, 2u, i)).v[OCTRACE_IN_PART(2u, i)];
}
GpuTriangle triangle_at(uint i) { return TrianglePart(OCTRACE_PART(SPLIT_TRIANGLES, 6u, i)).v[OCTRACE_IN_PART(6u, i)]; }
GpuTriangleNormals triangle_normals_at(uint i) {
  return TriangleNormalPart(OCTRACE_PART(SPLIT_TRIANGLE_NORMALS, 6u, i)).v[OCTRACE_IN_PART(6u, i)];
}
GpuTriangleUvs triangle_uvs_at(uint i) {
  return TriangleUvPart(OCTRACE_PART(SPLIT_TRIANGLE_UVS, 5u, i)).v[OCTRACE_IN_PART(5u, i)];
}
GpuOctreeNode node_at(uint i) { return NodePart(OCTRACE_PART(SPLIT_OCTREE_NODES, 5u, i)).v[OCTRACE_IN_PART(5u, i)]; }
uint ref_at(uint i) { return UintPart(OCTRACE_PART(SPLIT_OCTREE_REFS, 2u, i)).v[OCTRACE_IN_PART(2u, i)]; }
#if OCTRACE_PRECISION >= 1
OCTRACE_MATERIAL material_at(uint i) {
  return MaterialPart(OCTRACE_PART(SPLIT_MATERIALS_HALF, 6u, i)).v[OCTRACE_IN_PART(6u, i)];
}
#else
OCTRACE_MATERIAL material_at(uint i) {
  return MaterialPart(OCTRACE_PART(SPLIT_MATERIALS, 7u, i)).v[OCTRACE_IN_PART(7u, i)];
}
#endif

#else
// Spheres and nodes are declared as whole vectors (a sphere one vec4, a node
// two uvec4) and their structs built from them: NVIDIA's compiler loaded a
// node's 32 bytes in two 128-bit loads and then its two uint members again
// in four 4-byte loads, a sphere's radius twice, the loads of one struct
// split by member type (tools/nvidia_sass.py). Read as vectors, the BVH
// rendered 7-8% faster on the H200, the octree within 1% (optimisation log
// 62). The split form's buffer references keep the structs: not measured.
layout(std430, binding = BINDING_SPHERES) readonly buffer SphereBuf { vec4 spheres[]; };
layout(std430, binding = BINDING_SPHERE_MATERIALS) readonly buffer SphereMatBuf { uint sphere_materials[]; };
layout(std430, binding = BINDING_OCTREE_NODES) readonly buffer NodeBuf { uvec4 octree_nodes[]; };  // two per node
layout(std430, binding = BINDING_OCTREE_REFS) readonly buffer RefBuf { uint octree_refs[]; };
layout(std430, binding = BINDING_TRIANGLES) readonly buffer TriangleBuf { GpuTriangle triangles[]; };
layout(std430, binding = BINDING_TRIANGLE_NORMALS) readonly buffer TriangleNormalBuf { GpuTriangleNormals triangle_normals[]; };
layout(std430, binding = BINDING_TRIANGLE_UVS) readonly buffer TriangleUvBuf { GpuTriangleUvs triangle_uvs[]; };
layout(std430, binding = BINDING_MATERIALS) readonly buffer MaterialBuf { OCTRACE_MATERIAL materials[]; };

GpuSphere sphere_at(uint i) {
  vec4 s = spheres[i];
  return GpuSphere(s.xyz, s.w);
}
uint sphere_material_at(uint i) { return sphere_materials[i]; }
GpuTriangle triangle_at(uint i) { return triangles[i]; }
GpuTriangleNormals triangle_normals_at(uint i) { return triangle_normals[i]; }
GpuTriangleUvs triangle_uvs_at(uint i) { return triangle_uvs[i]; }
GpuOctreeNode node_at(uint i) {
  uvec4 lo_first = octree_nodes[2u * i], hi_count = octree_nodes[2u * i + 1u];
  return GpuOctreeNode(uintBitsToFloat(lo_first.xyz), lo_first.w, uintBitsToFloat(hi_count.xyz), hi_count.w);
}
uint ref_at(uint i) { return octree_refs[i]; }
OCTRACE_MATERIAL material_at(uint i) { return materials[i]; }
#endif

#endif
