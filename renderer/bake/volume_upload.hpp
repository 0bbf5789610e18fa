#pragma once
// Uploads a volume as a 3D texture of the value normalized over a window:
// texel = clamp((value - lo) / (hi - lo), 0, 1). R16_UNORM (two bytes per
// voxel whatever the source type), or R8_UNORM when that holds exactly the
// same numbers; both filterable on every Vulkan device.
#include "gpu/context.hpp"
#include "gpu/resources.hpp"
#include "volume/volume.hpp"

#include <array>
#include <cstddef>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

namespace cutaway::bake {

/// The values the texture holds, [lo, hi]; a voxel outside takes the nearer
/// end. `below` and `above`: the values such voxels are classified as (the
/// transfer table's first and last entries; none: lo and hi), the volume's
/// extremes where /volume/window cuts them off, so air below a soft-tissue
/// window stays air.
struct ValueWindow {
    double lo = 0.0;
    double hi = 1.0;
    std::optional<double> below;
    std::optional<double> above;
    bool operator==(const ValueWindow&) const = default;
};

/// A volume's texels. The value texture is R8_UNORM when every voxel's R16
/// texel is a multiple of 257 (its normalized value a multiple of 1/255, as
/// for an 8-bit scan over the window [0, 255] or a label volume over [0, 1]):
/// k/255 and 257k/65535 are the same number, in half the bytes. Integer
/// volumes of up to 16 bits are converted through a table by raw value.
class ValueTexels {
public:
    ValueTexels(const Volume& volume, ValueWindow window); ///< keeps a reference to `volume`
    VkFormat format() const { return m_r8 ? VK_FORMAT_R8_UNORM : VK_FORMAT_R16_UNORM; }
    std::size_t texelBytes() const { return m_r8 ? 1 : 2; }
    /// Writes the texels of voxels [first, first + count) in format() to `dst`.
    void write(std::size_t first, std::size_t count, std::byte* dst) const;
    /// The R16 texel of voxel i, whatever format() is.
    uint16_t r16(std::size_t i) const;

private:
    const Volume& m_volume;
    ValueWindow m_window;
    std::vector<uint16_t> m_table; ///< R16 texel by raw value + m_offset; empty: computed
    int m_offset = 0;
    bool m_r8 = false;
};

/// R16 texels (x fastest), the CPU reference in tests and the VTK comparison's input.
std::vector<uint16_t> normalizeVolume(const Volume& volume, ValueWindow window);

/// A 3D image of the values (ValueTexels), sampled by fragment and compute
/// shaders. With `storage` (gpu::DeviceTuning::storageValues, where the
/// device can: DeviceFormats::storageValues) it is a storage image too and
/// rests in GENERAL, so shaders may load its texels; else it rests in
/// SHADER_READ_ONLY_OPTIMAL. Image::layout says which.
gpu::Image uploadVolume(const gpu::Context& ctx, const Volume& volume, ValueWindow window,
                        bool storage);
/// The same with the device's tuning (Context::tuning).
gpu::Image uploadVolume(const gpu::Context& ctx, const Volume& volume, ValueWindow window);

/// The storage images of a shader built with CW_STORAGE_PATHS. GLSL fixes a
/// storage image's format in its declaration, so such a shader declares an
/// R8 and an R16 binding for the values and a specialization constant picks
/// the one it loads (sample_common.h's cwStorageFetch); each binding needs an
/// image, and so does the gradients' (sample_common.h's gradientImage). The
/// stand-ins are 1^3 images of those formats (RGBA8, never read, where the
/// device has no R8 and R16 storage images), made on first use: a device
/// whose tuning takes no storage paths makes none.
class ValueStorageBindings {
public:
    explicit ValueStorageBindings(const gpu::Context& ctx) : m_ctx(ctx) {}
    /// The views for the R8 and the R16 binding: `values` (from uploadVolume)
    /// in the one of its format where it is a storage image, a stand-in in
    /// the other (in both where it is not).
    std::array<VkImageView, 2> views(const gpu::Image& values);
    /// The view for the gradients' storage binding: `gradients` where they
    /// rest in GENERAL, else a stand-in.
    VkImageView gradientView(const gpu::Image& gradients);
    /// cwStorageFetch's value for `values`: 1 for R8, 2 for R16, 0 where it
    /// is no storage image (the shader must sample it).
    static int fetchOf(const gpu::Image& values) {
        if (!(values.usage & VK_IMAGE_USAGE_STORAGE_BIT)) return 0;
        return values.format == VK_FORMAT_R8_UNORM ? 1 : 2;
    }
    /// How many stand-ins this object has made (tests).
    int standIns() const;

private:
    const gpu::Image& standIn(int which);
    const gpu::Context& m_ctx;
    gpu::Image m_standIns[3]; ///< R8, R16, RGBA8_SNORM
};

/// A 0/1 mask (one byte per voxel, x fastest) as an R8_UNORM 3D image that
/// samples 0 or 1, like uploadVolume over the window [0, 1] at an eighth of
/// the work: no conversion, half the bytes. Sampled only, resting in
/// SHADER_READ_ONLY_OPTIMAL.
gpu::Image uploadMask(const gpu::Context& ctx, const std::vector<uint8_t>& mask, glm::ivec3 dims);
/// The same from texels that `write` makes (0 outside, 255 inside), so the
/// mask need not be whole on the host.
gpu::Image uploadMask(const gpu::Context& ctx, glm::ivec3 dims, const gpu::TexelWriter& write);

} // namespace cutaway::bake
