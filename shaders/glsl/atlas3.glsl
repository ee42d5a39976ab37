// A volume as a 2D atlas of its z slices (GLSL twin of shaders/atlas3.wgsl; Rust twins in
// analyzer/src/noise.rs): slice z of a volume whose slices are `size` texels lies at column
// z % 8, row z / 8. All operands are non-negative.

const int ATLAS_COLUMNS = 8;

ivec2 atlas_texel(ivec3 c, ivec2 size) {
    return ivec2(c.x + size.x * (c.z % ATLAS_COLUMNS), c.y + size.y * (c.z / ATLAS_COLUMNS));
}

ivec3 atlas_voxel(ivec2 t, ivec2 size) {
    int col = t.x / size.x;
    int row = t.y / size.y;
    return ivec3(t.x - col * size.x, t.y - row * size.y, col + ATLAS_COLUMNS * row);
}
