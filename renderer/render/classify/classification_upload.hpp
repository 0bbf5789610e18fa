#pragma once
// A scene's classification on the device: the transfer functions' tables (one
// layer per function) and each voxel's layer, read by the slicing shaders and
// the ray caster.
#include "gpu/context.hpp"
#include "gpu/resources.hpp"
#include "render/gpu_volume.hpp"
#include "scene/scene.hpp"

#include <cstdint>
#include <optional>
#include <vector>

namespace cutaway::render {

/// The classification tables, one layer per transfer function (/transfer,
/// then /transfer/labels; classifyingTransfers): the 1D function
/// (post-classification) or its pre-integrated 2D table for slabs `sliceMm`
/// thick, RGBA16F.
gpu::Image uploadTransfer(const gpu::Context& ctx, const Scene& scene, const GpuVolume& volume,
                          double sliceMm);

/// Each voxel's classification layer (R8_UINT), or a single 0 without labels;
/// with label channels (OutputSettings::labelAovs) the texels of
/// LabelChannelTexels (R32_UINT), whose lowest label id goes to `lowest`.
gpu::Image uploadClasses(const gpu::Context& ctx, const Scene& scene, const GpuVolume& volume,
                         std::int64_t& lowest);

/// The frame's tables and layers, remade only when what they come from
/// changes (a turntable keeps them: pre-integration costs ~35 ms a table).
class ClassificationTables {
public:
    explicit ClassificationTables(const gpu::Context& ctx) : m_ctx(ctx) {}
    /// Brings both up to date with `scene`'s classification of `volume` for
    /// slabs `sliceMm` thick.
    void update(const Scene& scene, const GpuVolume& volume, double sliceMm);
    const gpu::Image& transfer() const { return m_transfer; }
    const gpu::Image& classes() const { return m_classes; }
    /// The label volume's lowest id, when classes() holds label channels.
    std::int64_t lowestLabel() const { return m_lowestLabel; }

private:
    /// What uploadTransfer's table comes from.
    struct TransferKey {
        bool preintegrated = false;
        bake::ValueWindow window;
        double sliceMm = 0.0, unitMm = 0.0;      ///< the slab, and what alphas refer to
        std::vector<TransferFunction> functions; ///< classifyingTransfers
        bool operator==(const TransferKey&) const = default;
    };
    /// What uploadClasses's layers come from: the label volume and which
    /// labels take which function.
    struct ClassesKey {
        std::uint64_t volume = 0;
        std::vector<std::vector<std::int64_t>> ids; ///< per /transfer/labels entry
        bool channels = false;                      ///< label channels (LabelChannelTexels)
        std::vector<std::int64_t> mattes;           ///< their mattes' labels
        bool operator==(const ClassesKey&) const = default;
    };
    const gpu::Context& m_ctx;
    gpu::Image m_transfer;
    std::optional<TransferKey> m_transferKey;
    gpu::Image m_classes;
    std::optional<ClassesKey> m_classesKey;
    std::int64_t m_lowestLabel = 0;
};

} // namespace cutaway::render
