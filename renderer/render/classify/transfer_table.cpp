#include "render/classify/transfer_table.hpp"

#include <algorithm>

namespace cutaway::render {

std::vector<const TransferFunction*> classifyingTransfers(const Scene& scene, bool withLabels) {
    std::vector<const TransferFunction*> transfers{&scene.transfer};
    if (withLabels)
        for (const LabelTransfer& t : scene.labelTransfers)
            transfers.push_back(&t.transfer);
    return transfers;
}

glm::vec4 evaluateTransfer(const TransferFunction& tf, double value) {
    const auto& pts = tf.points;
    if (pts.empty()) return glm::vec4(0.0f);
    auto rgba = [](const TransferPoint& p) { return glm::vec4(p.color, p.alpha); };
    if (value <= pts.front().value) return rgba(pts.front());
    if (value >= pts.back().value) return rgba(pts.back());
    auto it = std::upper_bound(pts.begin(), pts.end(), value,
                               [](double v, const TransferPoint& p) { return v < p.value; });
    const TransferPoint& b = *it;
    const TransferPoint& a = *(it - 1);
    const float t = static_cast<float>((value - a.value) / (b.value - a.value));
    return glm::mix(rgba(a), rgba(b), t);
}

std::vector<glm::vec4> tabulateTransfer(const TransferFunction& tf, bake::ValueWindow window,
                                        int n) {
    std::vector<glm::vec4> table(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        double v = window.lo + (window.hi - window.lo) * i / (n - 1);
        if (i == 0) v = window.below.value_or(window.lo);
        if (i == n - 1) v = window.above.value_or(window.hi);
        table[static_cast<std::size_t>(i)] = evaluateTransfer(tf, v);
    }
    return table;
}

} // namespace cutaway::render
