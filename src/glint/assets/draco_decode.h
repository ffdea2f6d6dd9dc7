#pragma once
// Draco mesh decoding (glTF's KHR_draco_mesh_compression), in a shared module of its own:
// Debian's libdraco carries a copy of tinygltf (for its transcoder) whose symbols must never meet
// glint's tinygltf, so the module links the Draco archive privately and exports only this.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace glint {

struct DracoAttribute {
    int unique_id = 0;
    int components = 0;
    std::vector<float> values;  ///< components per point, normalised integers mapped to [0, 1] / [-1, 1]
};

struct DracoMesh {
    std::uint32_t points = 0;
    std::vector<std::uint32_t> indices;  ///< three point indices per triangle
    std::vector<DracoAttribute> attributes;
};

/// Decodes the Draco bitstream `data` (a triangle mesh); at most `max_values` attribute values
/// in all. Throws std::runtime_error with Draco's reason when it cannot.
[[gnu::visibility("default")]] DracoMesh decode_draco_mesh(const unsigned char* data, std::size_t size,
                                                           std::size_t max_values);

}  // namespace glint
