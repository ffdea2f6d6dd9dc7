#include "glint/assets/draco_decode.h"

#include <draco/compression/decode.h>

#include <stdexcept>
#include <string>

namespace glint {

DracoMesh decode_draco_mesh(const unsigned char* data, std::size_t size, std::size_t max_values) {
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(data), size);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok()) throw std::runtime_error(decoded.status().error_msg_string());
    const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
    if (!mesh) throw std::runtime_error("no mesh");
    DracoMesh out;
    out.points = mesh->num_points();
    std::size_t total = 0;
    for (int a = 0; a < mesh->num_attributes(); ++a) {
        const draco::PointAttribute* attribute = mesh->attribute(a);
        const int n = attribute->num_components();
        if (n < 1 || n > 4) throw std::runtime_error("an attribute of " + std::to_string(n) + " components");
        total += static_cast<std::size_t>(n) * out.points;
        if (total > max_values) throw std::runtime_error("more attribute values than the limit of " + std::to_string(max_values));
        DracoAttribute d{static_cast<int>(attribute->unique_id()), n, {}};
        d.values.resize(static_cast<std::size_t>(n) * out.points);
        for (draco::PointIndex i(0); i < mesh->num_points(); ++i)
            if (!attribute->ConvertValue<float>(attribute->mapped_index(i), static_cast<std::int8_t>(n),
                                                d.values.data() + static_cast<std::size_t>(i.value()) * n))
                throw std::runtime_error("attribute " + std::to_string(d.unique_id) + " cannot be read as numbers");
        out.attributes.push_back(std::move(d));
    }
    if (3 * static_cast<std::size_t>(mesh->num_faces()) > max_values)
        throw std::runtime_error("more faces than the limit allows");
    out.indices.reserve(3 * static_cast<std::size_t>(mesh->num_faces()));
    for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
        for (int k = 0; k < 3; ++k) out.indices.push_back(mesh->face(f)[k].value());
    return out;
}

}  // namespace glint
