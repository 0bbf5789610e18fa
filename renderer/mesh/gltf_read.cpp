// Checked reads of glTF accessors; see gltf_detail.hpp.
#include "core/error.hpp"
#include "mesh/gltf_detail.hpp"

#include <bit>
#include <cmath>
#include <cstring>
#include <tiny_gltf.h>

namespace cutaway::mesh::detail {
namespace {

// glTF buffers are little-endian; values are copied out as they lie.
static_assert(std::endian::native == std::endian::little, "glTF reading assumes little-endian");

// The bytes of one accessor: `count` elements, `stride` bytes apart.
struct Elements {
    const unsigned char* data = nullptr;
    std::size_t stride = 0;
    std::size_t count = 0;
    int componentType = 0;
    int type = 0;
    bool normalized = false;
};

std::string componentName(int componentType) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
        return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT:
        return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return "FLOAT";
    default:
        return "component type " + std::to_string(componentType);
    }
}

std::string typeName(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR:
        return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
        return "VEC2";
    case TINYGLTF_TYPE_VEC3:
        return "VEC3";
    case TINYGLTF_TYPE_VEC4:
        return "VEC4";
    default:
        return "a matrix type";
    }
}

// Validates the byte range accessor `index` reads. The caller has already
// checked the index (accessorAt) and that componentType and type are ones it
// can read, so the element size is known and small.
Elements locate(const tinygltf::Model& model, int index, const std::string& what) {
    const std::string name = what + " accessor " + std::to_string(index);
    const tinygltf::Accessor& acc = model.accessors[index];
    if (acc.bufferView < 0)
        throw InputError(name + " has no bufferView (all-zero data is not supported)");
    if (static_cast<std::size_t>(acc.bufferView) >= model.bufferViews.size()) {
        throw InputError(name + " refers to bufferView " + std::to_string(acc.bufferView) +
                         ", which does not exist");
    }
    const tinygltf::BufferView& view = model.bufferViews[acc.bufferView];
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size()) {
        throw InputError(what + ": bufferView " + std::to_string(acc.bufferView) +
                         " refers to buffer " + std::to_string(view.buffer) +
                         ", which does not exist");
    }
    const std::vector<unsigned char>& buffer = model.buffers[view.buffer].data;

    const std::size_t componentSize =
        static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(acc.componentType));
    const std::size_t elementSize =
        componentSize * static_cast<std::size_t>(tinygltf::GetNumComponentsInType(acc.type));
    const std::size_t stride = view.byteStride != 0 ? view.byteStride : elementSize;
    if (stride < elementSize) {
        throw InputError(name + ": bufferView " + std::to_string(acc.bufferView) +
                         " has byteStride " + std::to_string(stride) +
                         ", less than the element size " + std::to_string(elementSize));
    }
    Elements e{nullptr, stride, acc.count, acc.componentType, acc.type, acc.normalized};
    if (acc.count == 0) return e;

    // start + stride * (count - 1) + elementSize, each step checked for
    // overflow: the offsets and the count are whatever the file says.
    std::size_t start = 0, span = 0, end = 0, viewEnd = 0;
    const bool overflow = __builtin_add_overflow(view.byteOffset, acc.byteOffset, &start) ||
                          __builtin_mul_overflow(stride, acc.count - 1, &span) ||
                          __builtin_add_overflow(start, span, &end) ||
                          __builtin_add_overflow(end, elementSize, &end);
    if (overflow || end > buffer.size()) {
        throw InputError(name + " reads past the end of buffer " + std::to_string(view.buffer) +
                         " (" + std::to_string(buffer.size()) + " bytes)");
    }
    if (__builtin_add_overflow(view.byteOffset, view.byteLength, &viewEnd) || end > viewEnd) {
        throw InputError(name + " reads past the end of bufferView " +
                         std::to_string(acc.bufferView));
    }
    e.data = buffer.data() + start;
    return e;
}

std::string formatOf(const tinygltf::Accessor& acc) {
    return componentName(acc.componentType) + " " + typeName(acc.type);
}

const tinygltf::Accessor& accessorAt(const tinygltf::Model& model, int index,
                                     const std::string& what) {
    if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size())
        throw InputError(what + ": accessor " + std::to_string(index) + " does not exist");
    if (model.accessors[index].sparse.isSparse) {
        throw InputError(what + " accessor " + std::to_string(index) +
                         ": sparse accessors are not supported");
    }
    return model.accessors[index];
}

template <typename T>
T load(const unsigned char* p) {
    T value;
    std::memcpy(&value, p, sizeof(T)); // buffers need not be aligned for T
    return value;
}

// Component c of element i as a float; integer components are normalized.
float component(const Elements& e, std::size_t i, int c) {
    const unsigned char* p = e.data + i * e.stride;
    switch (e.componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return static_cast<float>(load<std::uint8_t>(p + c)) / 255.0f;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return static_cast<float>(load<std::uint16_t>(p + 2 * c)) / 65535.0f;
    default:
        return load<float>(p + 4 * c);
    }
}

} // namespace

std::vector<glm::vec3> readVec3(const tinygltf::Model& model, int accessor,
                                const std::string& what) {
    const tinygltf::Accessor& acc = accessorAt(model, accessor, what);
    if (acc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || acc.type != TINYGLTF_TYPE_VEC3) {
        throw InputError(what + " accessor " + std::to_string(accessor) +
                         " must be FLOAT VEC3, not " + formatOf(acc));
    }
    const Elements e = locate(model, accessor, what);
    std::vector<glm::vec3> out(e.count);
    for (std::size_t i = 0; i < e.count; ++i) {
        for (int c = 0; c < 3; ++c)
            out[i][c] = component(e, i, c);
        if (!std::isfinite(out[i].x) || !std::isfinite(out[i].y) || !std::isfinite(out[i].z)) {
            throw InputError(what + " accessor " + std::to_string(accessor) +
                             " has a non-finite value in element " + std::to_string(i));
        }
    }
    return out;
}

std::vector<glm::vec4> readColors(const tinygltf::Model& model, int accessor,
                                  const std::string& what) {
    const tinygltf::Accessor& acc = accessorAt(model, accessor, what);
    // The spec requires `normalized` on integer colours; it is not demanded
    // here since an integer colour can mean nothing else.
    const bool readable = acc.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                          acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                          acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    if (!readable || (acc.type != TINYGLTF_TYPE_VEC3 && acc.type != TINYGLTF_TYPE_VEC4)) {
        throw InputError(what + " accessor " + std::to_string(accessor) +
                         " must be FLOAT, UNSIGNED_BYTE or UNSIGNED_SHORT VEC3 or VEC4, not " +
                         formatOf(acc));
    }
    const Elements e = locate(model, accessor, what);
    const int channels = acc.type == TINYGLTF_TYPE_VEC4 ? 4 : 3;
    std::vector<glm::vec4> out(e.count, glm::vec4(1.0f));
    for (std::size_t i = 0; i < e.count; ++i) {
        for (int c = 0; c < channels; ++c) {
            out[i][c] = component(e, i, c);
            if (!std::isfinite(out[i][c])) {
                throw InputError(what + " accessor " + std::to_string(accessor) +
                                 " has a non-finite value in element " + std::to_string(i));
            }
        }
    }
    return out;
}

std::vector<std::uint32_t> readIndices(const tinygltf::Model& model, int accessor,
                                       const std::string& what) {
    const tinygltf::Accessor& acc = accessorAt(model, accessor, what);
    const int ct = acc.componentType;
    if (acc.type != TINYGLTF_TYPE_SCALAR || (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                                             ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                                             ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)) {
        throw InputError(what + " accessor " + std::to_string(accessor) +
                         " must be UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT SCALAR, not " +
                         formatOf(acc));
    }
    const Elements e = locate(model, accessor, what);
    std::vector<std::uint32_t> out(e.count);
    for (std::size_t i = 0; i < e.count; ++i) {
        const unsigned char* p = e.data + i * e.stride;
        if (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE)
            out[i] = load<std::uint8_t>(p);
        else if (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)
            out[i] = load<std::uint16_t>(p);
        else
            out[i] = load<std::uint32_t>(p);
    }
    return out;
}

} // namespace cutaway::mesh::detail
