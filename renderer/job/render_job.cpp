#include "job/render_job.hpp"

#include "core/error.hpp"
#include "job/address_space.hpp"
#include "job/scene_check.hpp"
#include "render/gpu_volume.hpp"
#include "render/volume_renderer.hpp"
#include "volume/phantom.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace cutaway::job {

Volume loadSceneVolume(const Scene& scene, std::size_t* nonFinite) {
    const VolumeSource& src = scene.volume;
    Volume volume;
    if (!src.phantom.empty())
        volume = makePhantom(src.phantom, src.phantomSize).values;
    else if (src.raw)
        volume = readRaw(src.file, *src.raw);
    else
        volume = readVolume(src.file);
    if (src.spacing) volume.spacing = *src.spacing;
    // After the value range (which leaves them out) is known: the window and
    // empty space's value come from the finite voxels.
    const std::size_t replaced = replaceNonFinite(volume, emptyValue(scene, volume));
    if (nonFinite) *nonFinite = replaced;
    return volume;
}

std::string nonFiniteWarning(const Scene& scene, std::size_t count, std::size_t voxels) {
    return "/volume/file: " + scene.volume.file.string() + ": " +
           (count == voxels ? "all " + std::to_string(count) + " voxels are"
            : count == 1    ? "1 voxel is"
                            : std::to_string(count) + " voxels are") +
           " not finite (NaN or infinite): left out of the value range and the automatic "
           "window, rendered as empty";
}

namespace {

// Checks labels (read or made) against the scan's grid; see loadSceneLabels.
void checkLabels(const Scene& scene, const Volume& labels, const Volume& scan) {
    const LabelSource& src = *scene.labels;
    const std::string name =
        src.phantom ? "the " + scene.volume.phantom + " phantom's labels" : src.file.string();
    const auto text = [](auto v) {
        std::ostringstream out;
        out << v.x << " x " << v.y << " x " << v.z;
        return out.str();
    };
    if (labels.dims != scan.dims)
        throw InputError(name + ": the label volume's grid is " + text(labels.dims) +
                         " voxels, the scan's " + text(scan.dims) +
                         "; labels must be on the scan's grid");
    const glm::dvec3 ratio = labels.spacing / scan.spacing;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(ratio[a] - 1.0) > 1e-3)
            throw InputError(name + ": the label volume's spacing is " + text(labels.spacing) +
                             " mm, the scan's " + text(scan.spacing) +
                             " mm; labels must be on the scan's grid");
    }
    if (labels.type == VoxelType::F32 || labels.type == VoxelType::F64 || labels.slope != 1.0 ||
        labels.inter != 0.0)
        throw InputError(name + ": label ids must be stored as integers (got " +
                         std::string(voxelTypeName(labels.type)) +
                         (labels.slope != 1.0 || labels.inter != 0.0 ? " with scaling" : "") + ")");
    if (valueRange(labels).min < 0.0) throw InputError(name + ": label ids must not be negative");
}

std::shared_ptr<const Volume> checkedLabels(const Scene& scene, Volume read, const Volume& scan) {
    auto labels = std::make_shared<Volume>(std::move(read));
    if (scene.volume.spacing) labels->spacing = *scene.volume.spacing;
    checkLabels(scene, *labels, scan);
    return labels;
}

// Whether /labels names the file /volume reads (as a volume file, not raw).
bool labelsAreTheScan(const Scene& scene) {
    if (!scene.labels || scene.labels->phantom || !scene.volume.phantom.empty() || scene.volume.raw)
        return false;
    std::error_code ec;
    return std::filesystem::equivalent(scene.labels->file, scene.volume.file, ec) && !ec;
}

} // namespace

std::shared_ptr<const Volume> loadSceneLabels(const Scene& scene,
                                              const std::shared_ptr<const Volume>& scan) {
    if (!scene.labels) return nullptr;
    if (labelsAreTheScan(scene)) {
        checkLabels(scene, *scan, *scan);
        return scan;
    }
    return checkedLabels(scene,
                         scene.labels->phantom
                             ? makePhantom(scene.volume.phantom, scene.volume.phantomSize).labels
                             : readVolume(scene.labels->file),
                         *scan);
}

bake::ValueWindow sceneWindow(const Scene& scene, const Volume& volume) {
    if (scene.volume.window) return {(*scene.volume.window)[0], (*scene.volume.window)[1]};
    const ValueRange range = valueRange(volume);
    if (range.max > range.min) return {range.min, range.max};
    return {range.min, range.min + 1.0};
}

float emptyValue(const Scene& scene, const Volume& scan) {
    return static_cast<float>(std::min(sceneWindow(scene, scan).lo, valueRange(scan).min));
}

bool sequential(const Scene& scene) {
    return scene.render.composition == Composition::Sequential && scene.operators.size() > 1;
}

FrameVolume frameVolume(const Scene& scene) {
    // A phantom with its own labels is generated once, for both.
    std::optional<Volume> phantomLabels;
    Volume scan;
    std::size_t nonFinite = 0;
    if (scene.labels && scene.labels->phantom && !sequential(scene)) {
        Phantom phantom = makePhantom(scene.volume.phantom, scene.volume.phantomSize);
        scan = std::move(phantom.values);
        if (scene.volume.spacing) scan.spacing = *scene.volume.spacing;
        phantomLabels = std::move(phantom.labels);
    } else {
        scan = loadSceneVolume(scene, &nonFinite);
    }
    const bake::ValueWindow window = sceneWindow(scene, scan);
    const float empty = sequential(scene) ? emptyValue(scene, scan) : 0.0f;
    operators::PlacedVolume placed = operators::centred(std::move(scan));
    if (sequential(scene)) {
        const std::vector<OperatorSpec> baked(scene.operators.begin(), scene.operators.end() - 1);
        placed = operators::resampleSequentially(placed, baked, empty);
    }
    auto shared = std::make_shared<const Volume>(std::move(placed.volume));
    // Sequential composition with several operators resamples the scan but
    // not its labels, which no longer match it: the frame has none (the
    // parser refuses what would need them).
    std::shared_ptr<const Volume> labels =
        sequential(scene) ? nullptr
        : phantomLabels   ? checkedLabels(scene, std::move(*phantomLabels), *shared)
                          : loadSceneLabels(scene, shared);
    return FrameVolume{std::move(shared), placed.worldLo, window, std::move(labels), nonFinite};
}

std::string frameVolumeKey(const Scene& scene) {
    // Built from the parsed scene, not its JSON, so scenes made in code work too.
    const VolumeSource& v = scene.volume;
    std::ostringstream key;
    key.precision(17);
    key << v.file.string() << '|' << v.phantom << '|' << v.phantomSize.x << ',' << v.phantomSize.y
        << ',' << v.phantomSize.z;
    if (v.raw)
        key << "|raw " << v.raw->dims.x << ',' << v.raw->dims.y << ',' << v.raw->dims.z << ','
            << voxelTypeName(v.raw->type) << ',' << v.raw->spacing.x << ',' << v.raw->spacing.y
            << ',' << v.raw->spacing.z << ',' << v.raw->bigEndian << ',' << v.raw->offset;
    if (v.spacing) key << "|spacing " << v.spacing->x << ',' << v.spacing->y << ',' << v.spacing->z;
    if (v.window) key << "|window " << (*v.window)[0] << ',' << (*v.window)[1];
    if (scene.labels) key << "|labels " << scene.labels->file.string() << scene.labels->phantom;
    if (sequential(scene)) { // the operators baked into the intermediate volume
        for (std::size_t i = 0; i + 1 < scene.operators.size(); ++i) {
            const OperatorSpec& op = scene.operators[i];
            key << "|op";
            for (int c = 0; c < 4; ++c)
                key << ' ' << op.params.a[c] << ' ' << op.params.b[c] << ' ' << op.params.kind[c];
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r)
                    key << ' ' << op.localToWorld[c][r];
        }
    }
    return key.str();
}

std::vector<OperatorSpec> liveOperators(const Scene& scene) {
    if (!sequential(scene)) return scene.operators;
    return {scene.operators.back()};
}

namespace {

// A frame number's place in a pattern: a run of '#', or "%d", "%Nd", "%0Nd".
struct Placeholder {
    std::size_t position = 0, length = 0; ///< of the placeholder's text
    std::size_t width = 0;                ///< digits the number is padded to
    char fill = '0';
};

// Wider than any file name may be; keeps a width such as "%99999999999d"
// from overflowing. checkOutputPaths refuses the name it makes.
constexpr std::size_t kMaxWidth = 4096;

// A '%' that starts a placeholder, or "%%", which stands for '%' as in printf.
struct PatternScan {
    std::vector<Placeholder> placeholders;
    std::vector<std::size_t> percents; ///< where each "%%" starts
};

PatternScan scan(const std::string& p) {
    PatternScan out;
    std::size_t i = 0;
    while (i < p.size()) {
        if (p[i] == '#') {
            const std::size_t end = std::min(p.find_first_not_of('#', i), p.size());
            out.placeholders.push_back({i, end - i, end - i, '0'});
            i = end;
            continue;
        }
        if (p[i] == '%' && i + 1 < p.size() && p[i + 1] == '%') {
            out.percents.push_back(i);
            i += 2;
            continue;
        }
        if (p[i] == '%') {
            std::size_t j = i + 1, width = 0;
            const char fill = j < p.size() && p[j] == '0' ? '0' : ' ';
            if (fill == '0') ++j;
            for (; j < p.size() && p[j] >= '0' && p[j] <= '9'; ++j)
                width = std::min(width * 10 + std::size_t(p[j] - '0'), kMaxWidth);
            if (j < p.size() && p[j] == 'd') {
                out.placeholders.push_back({i, j + 1 - i, width, fill});
                i = j + 1;
                continue;
            }
        }
        ++i;
    }
    return out;
}

// `frame` in decimal, padded to `width` with zeros or spaces.
std::string padded(int frame, std::size_t width, char fill) {
    std::string digits = std::to_string(frame);
    if (digits.size() < width) digits.insert(0, width - digits.size(), fill);
    return digits;
}

} // namespace

std::string expandPattern(const std::string& pattern, int frame) {
    const PatternScan found = scan(pattern);
    std::string out;
    std::size_t from = 0, h = 0, q = 0;
    // Placeholders and "%%" do not overlap; take them in the order they come.
    while (h < found.placeholders.size() || q < found.percents.size()) {
        const bool hole =
            q == found.percents.size() ||
            (h < found.placeholders.size() && found.placeholders[h].position < found.percents[q]);
        const std::size_t at = hole ? found.placeholders[h].position : found.percents[q];
        out += pattern.substr(from, at - from);
        if (hole) {
            const Placeholder& ph = found.placeholders[h++];
            out += padded(frame, ph.width, ph.fill);
            from = at + ph.length;
        } else {
            out += '%';
            from = at + 2;
            ++q;
        }
    }
    return out + pattern.substr(from);
}

int framePlaceholders(const std::string& pattern) {
    return static_cast<int>(scan(pattern).placeholders.size());
}

std::filesystem::path previewPath(const std::filesystem::path& exrPath) {
    std::filesystem::path p = exrPath;
    p.replace_extension(".png");
    return p;
}

void applyOverrides(Scene& scene, const RenderOverrides& overrides) {
    if (overrides.outputPattern) scene.output.pattern = *overrides.outputPattern;
    if (overrides.size) {
        scene.render.width = overrides.size->x;
        scene.render.height = overrides.size->y;
    }
    if (overrides.png) scene.output.png = true;
}

FrameRenderer::FrameRenderer(const gpu::Context& ctx) : m_ctx(ctx), m_baker(ctx), m_renderer(ctx) {}

Image FrameRenderer::render(const Scene& scene) {
    // Same key, same volume: its texture and gradients are kept.
    const std::string key = frameVolumeKey(scene);
    if (!m_volume || key != m_volumeKey) {
        m_volume.reset(); // free the old textures before making new ones
        FrameVolume fv = frameVolume(scene);
        // Before the upload and the pipelines: past the limit, the driver fails inside.
        checkAddressSpace(addressSpaceNeed(scene, fv.scan.get(), fv.labels.get()));
        const glm::ivec3 dims = fv.scan->dims;
        if (fv.nonFinite > 0 && m_warnedNonFinite.insert(key).second)
            m_warnings.push_back(nonFiniteWarning(scene, fv.nonFinite, fv.scan->voxelCount()));
        try {
            m_volume = std::make_unique<render::GpuVolume>(render::prepareVolume(
                m_ctx, m_baker, std::move(fv.scan), fv.window, fv.worldLo, std::move(fv.labels)));
        } catch (const ResourceError& e) {
            const VolumeSource& v = scene.volume;
            throw ResourceError("the volume " +
                                (v.phantom.empty() ? v.file.string() : "phantom " + v.phantom) +
                                " (" + std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
                                std::to_string(dims.z) + ") does not fit: " + e.what());
        }
        m_volumeKey = key;
        ++m_uploads;
    } else {
        checkAddressSpace(addressSpaceNeed(scene, m_volume->scan.get(), m_volume->labels.get()));
    }
    warnOfOperatorsOutside(scene);
    Scene live = scene;
    // Attached meshes are placed in the world first: under sequential
    // composition the live operators are a suffix of the scene's.
    for (MeshSpec& mesh : live.meshes) {
        if (!mesh.attach) continue;
        const auto& op = scene.operators[static_cast<std::size_t>(*mesh.attach)];
        mesh.placement = render::operatorFrame(op.localToWorld) * mesh.placement;
        mesh.attach.reset();
    }
    live.operators = liveOperators(scene);
    Image image = m_renderer.render(live, *m_volume);
    // The renderer counts the live operators; operator_id names each by its
    // index in the scene, and the live ones are the scene's last.
    const auto first = static_cast<float>(scene.operators.size() - live.operators.size());
    for (float& id : image.operatorIds)
        if (id >= 0.0f) id += first;
    return image;
}

void FrameRenderer::warnOfOperatorsOutside(const Scene& scene) {
    // The operator's own box V_T (not where it moves material to): when it
    // misses the volume's box, nothing is cut, moved or kept.
    for (OperatorOutside& o : operatorsOutside(scene, m_volume->box.lo, m_volume->box.hi))
        if (m_warnedOutside.insert(o.index).second) m_warnings.push_back(std::move(o.message));
}

Image renderImage(const gpu::Context& ctx, const Scene& scene) {
    return FrameRenderer(ctx).render(scene);
}

} // namespace cutaway::job
