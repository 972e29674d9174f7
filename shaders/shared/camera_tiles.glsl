// The camera's tiles (RenderSettings::camera_tiles; shared.h
// BINDING_CAMERA_TILES): their buffer and where a tile's count and list
// lie, for camera_tiles.comp, which writes them, and path_trace.comp,
// which reads them. The includer declares `pass` (PassParams).
#ifndef OCTRACE_CAMERA_TILES_GLSL
#define OCTRACE_CAMERA_TILES_GLSL

layout(std430, binding = BINDING_CAMERA_TILES) buffer CameraTileBuf { uint camera_tiles[]; };

// Tiles across the image, and in all (the lists follow the counts).
uint camera_tiles_across() { return (pass.width + CAMERA_TILE_PIXELS - 1u) / CAMERA_TILE_PIXELS; }
uint camera_tile_total() {
  return camera_tiles_across() * ((pass.height + CAMERA_TILE_PIXELS - 1u) / CAMERA_TILE_PIXELS);
}

uint camera_tile_of(uvec2 pixel) {
  return (pixel.y / CAMERA_TILE_PIXELS) * camera_tiles_across() + pixel.x / CAMERA_TILE_PIXELS;
}
#endif
