#include "job/value_checks.hpp"

#include "job/scene_data.hpp"
#include "render/classify/transfer_table.hpp"
#include "volume/otsu.hpp"

#include <cmath>
#include <limits>
#include <sstream>

namespace cutaway::job {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string number(double v) {
    std::ostringstream out;
    out.precision(6);
    out << v;
    return out.str();
}

std::string span(double lo, double hi) {
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict, its bug
    // 105329) of "[" + std::string once this is inlined.
    std::string text(1, '[');
    text += number(lo);
    text += ", ";
    text += number(hi);
    text += ']';
    return text;
}

// The range warnings of one transfer function at `pointer`.
void checkTransfer(const TransferFunction& tf, const std::string& pointer, ValueRange range,
                   std::vector<std::string>& out) {
    if (tf.points.empty()) return;
    const VisiblePart visible = visiblePart(tf);
    const std::string values = "the volume's values span " + span(range.min, range.max);
    if (visible.any && (visible.hi < range.min || visible.lo > range.max)) {
        out.push_back(pointer + ": the transfer function is visible only in " +
                      span(visible.lo, visible.hi) + ", and " + values +
                      ": nothing shows; set its points in the volume's units");
        return;
    }
    const double first = tf.points.front().value, last = tf.points.back().value;
    const double width = range.max - range.min;
    // Points in 0..1 on values a hundred times wider: one voxel value in a
    // hundred has its own colour (a label map of a few ids is meant so).
    if (first >= 0.0 && last <= 1.0 && width >= 100.0)
        out.push_back(pointer + ": the transfer function's points lie in " + span(first, last) +
                      ", and " + values + ": its points are in the volume's units, not 0..1" +
                      " (every value past its last point takes that point's colour)");
}

// How many voxels outside the window are drawn visible where their own value
// is not, or the other way round: they classify as the volume's extreme
// beyond that end (sceneWindow), which lies on the other side of a visible band.
std::size_t clampedChanged(const TransferFunction& tf, const Volume& scan,
                           const bake::ValueWindow& w) {
    const auto visible = [&](double v) { return render::evaluateTransfer(tf, v).w > 0.0f; };
    const bool below = visible(w.below.value_or(w.lo)), above = visible(w.above.value_or(w.hi));
    std::size_t count = 0;
    for (std::size_t i = 0; i < scan.voxelCount(); ++i) {
        const double v = scan.value(i);
        if ((v < w.lo && visible(v) != below) || (v > w.hi && visible(v) != above)) ++count;
    }
    return count;
}

} // namespace

VisiblePart visiblePart(const TransferFunction& tf) {
    VisiblePart part;
    const auto& p = tf.points;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (p[i].alpha <= 0.0f) continue;
        // Visible from the point before it (alpha rises from 0 there), or
        // from -inf for the first point; up to the point after it, or +inf.
        const double lo = i == 0 ? -kInf : p[i - 1].value;
        const double hi = i + 1 == p.size() ? kInf : p[i + 1].value;
        part.lo = part.any ? std::min(part.lo, lo) : lo;
        part.hi = part.any ? std::max(part.hi, hi) : hi;
        part.any = true;
    }
    return part;
}

std::vector<std::string> valueWarnings(const Scene& scene, const Volume& scan) {
    std::vector<std::string> out;
    const ValueRange range = valueRange(scan);
    checkTransfer(scene.transfer, "/transfer/points", range, out);
    for (std::size_t i = 0; i < scene.labelTransfers.size(); ++i)
        checkTransfer(scene.labelTransfers[i].transfer,
                      "/transfer/labels/" + std::to_string(i) + "/points", range, out);
    if (scene.volume.window) {
        const bake::ValueWindow w = sceneWindow(scene, range);
        if (const std::size_t n = clampedChanged(scene.transfer, scan, w); n > 0)
            out.push_back("/volume/window: " + std::to_string(n) + " voxels (" +
                          number(100.0 * double(n) / double(scan.voxelCount())) +
                          " %) lie outside " + span(w.lo, w.hi) +
                          " where /transfer shows some values and not others; they are drawn "
                          "as the volume's extreme beyond the window, " +
                          span(w.below.value_or(w.lo), w.above.value_or(w.hi)) +
                          ", so their visibility changes: widen the window to hold them");
    }
    return out;
}

std::vector<std::string> valueNotes(const Scene& scene, const Volume& scan) {
    std::vector<std::string> notes;
    const ValueRange range = valueRange(scan);
    notes.push_back("the volume's values span " + span(range.min, range.max));
    const bake::ValueWindow window = sceneWindow(scene, range);
    if (scene.volume.window)
        notes.push_back("/volume/window: the texture holds " + span(window.lo, window.hi));
    std::optional<double> otsu;
    for (const OperatorSpec& op : scene.operators) {
        if (op.alignment.mode != AlignmentMode::Surface || op.alignment.threshold) continue;
        if (!otsu) otsu = otsuThreshold(scan);
        notes.push_back("/operators/" + std::to_string(op.index) +
                        "/alignment/threshold: Otsu's threshold of the volume is " + number(*otsu));
    }
    return notes;
}

ValueChecks::Key ValueChecks::keyOf(const Scene& scene, std::uint64_t scanId, bool forNotes) {
    Key key;
    key.scan = scanId;
    key.window = scene.volume.window;
    if (forNotes) {
        for (const OperatorSpec& op : scene.operators)
            if (op.alignment.mode == AlignmentMode::Surface && !op.alignment.threshold)
                key.otsuOperators.push_back(op.index);
        return key;
    }
    key.transfers.push_back(scene.transfer);
    for (const LabelTransfer& t : scene.labelTransfers)
        key.transfers.push_back(t.transfer);
    return key;
}

const std::vector<std::string>& ValueChecks::warnings(const Scene& scene, const Volume& scan,
                                                      std::uint64_t scanId) {
    return cached(m_warningsKey, m_warnings, keyOf(scene, scanId, false),
                  [&] { return valueWarnings(scene, scan); });
}

const std::vector<std::string>& ValueChecks::notes(const Scene& scene, const Volume& scan,
                                                   std::uint64_t scanId) {
    return cached(m_notesKey, m_notes, keyOf(scene, scanId, true),
                  [&] { return valueNotes(scene, scan); });
}

} // namespace cutaway::job
