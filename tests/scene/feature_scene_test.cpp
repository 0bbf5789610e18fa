// Parsing of feature alignment (/operators/N/alignment), label volumes
// (/labels) and classification by label (/transfer/labels).
#include "scene/scene.hpp"
#include "scene_test_util.hpp"

#include <gtest/gtest.h>

namespace cutaway::test {
namespace {

using nlohmann::json;

const char* kTransfer = R"("points": [{"value": 0, "color": [1, 1, 1], "alpha": 0},
                                      {"value": 255, "color": [1, 1, 1], "alpha": 1}])";

std::string peeler(const std::string& alignment) {
    return R"({"operators": [{"type": "peeler", "placement": {"scale": [40, 40, 20]},
               "alignment": )" +
           alignment + "}]";
}

Scene parseWith(const std::string& patch) {
    return parseScene(patched(patch), "/nonexistent", "scene.json");
}

TEST(FeatureScene, AxisIsTheDefault) {
    const Scene scene =
        parseWith(R"({"operators": [{"type": "peeler", "placement": {"scale": [40, 40, 20]}}]})");
    EXPECT_EQ(scene.operators[0].alignment.mode, AlignmentMode::Axis);
}

TEST(FeatureScene, SurfaceAlignmentReadsThresholdDepthAndBand) {
    Scene scene = parseWith(
        peeler(R"({"mode": "surface", "threshold": 40, "depth": 6.5, "band": 1.5})") + "}");
    const Alignment& a = scene.operators[0].alignment;
    EXPECT_EQ(a.mode, AlignmentMode::Surface);
    ASSERT_TRUE(a.threshold);
    EXPECT_EQ(*a.threshold, 40.0);
    EXPECT_EQ(a.depth, 6.5);
    EXPECT_EQ(a.band, 1.5);
    scene = parseWith(peeler(R"({"mode": "surface", "threshold": "otsu"})") + "}");
    EXPECT_FALSE(scene.operators[0].alignment.threshold); // Otsu, found at render time
    EXPECT_EQ(scene.operators[0].alignment.depth, 5.0);
}

TEST(FeatureScene, SegmentAlignmentResolvesLabelNames) {
    const Scene scene = parseWith(
        R"({"labels": {"phantom": true},)" +
        peeler(R"({"mode": "segment", "labels": ["brain", 2], "band": 3})").substr(1) + "}");
    ASSERT_TRUE(scene.labels);
    EXPECT_TRUE(scene.labels->phantom);
    const Alignment& a = scene.operators[0].alignment;
    EXPECT_EQ(a.mode, AlignmentMode::Segment);
    EXPECT_EQ(a.labels, (std::vector<std::int64_t>{3, 2}));
    EXPECT_EQ(a.band, 3.0);
}

TEST(FeatureScene, SegmentAlignmentByValueRange) {
    const Scene scene = parseWith(peeler(R"({"mode": "segment", "range": [150, 255]})") + "}");
    const Alignment& a = scene.operators[0].alignment;
    ASSERT_TRUE(a.range);
    EXPECT_EQ((*a.range)[0], 150.0);
    EXPECT_TRUE(a.labels.empty());
}

TEST(FeatureScene, LabelNamesCanBeGivenAndIdsBeyond255Work) {
    const Scene scene = parseWith(
        R"({"labels": {"phantom": true, "names": {"cortex": 12175}},
            "transfer": {)" +
        std::string(kTransfer) + R"(, "labels": [{"labels": ["cortex", "skull"], )" + kTransfer +
        "}]}}");
    ASSERT_EQ(scene.labelTransfers.size(), 1u);
    EXPECT_EQ(scene.labelTransfers[0].ids, (std::vector<std::int64_t>{12175, 2}));
    EXPECT_EQ(scene.labelTransfers[0].transfer.points.size(), 2u);
}

// A pattern selects every name it matches (in the names' order); one that
// matches none is an error with the closest name, as an unknown name is.
TEST(FeatureScene, LabelPatternsSelectEveryMatchingName) {
    const auto labelsOf = [](const std::string& list) {
        return R"({"labels": {"phantom": true, "names": {"Frontal_L": 11, "Frontal_R": 12,
                   "Occipital_L": 21}}, "transfer": {)" +
               std::string(kTransfer) + R"(, "labels": [{"labels": )" + list + ", " + kTransfer +
               "}]}}";
    };
    EXPECT_EQ(parseWith(labelsOf(R"(["Frontal_*"])")).labelTransfers[0].ids,
              (std::vector<std::int64_t>{11, 12}));
    EXPECT_EQ(parseWith(labelsOf(R"(["*_L", "brain"])")).labelTransfers[0].ids,
              (std::vector<std::int64_t>{11, 21, 3}));
    EXPECT_EQ(parseWith(labelsOf(R"(["s?ull", "[bs]kin"])")).labelTransfers[0].ids,
              (std::vector<std::int64_t>{2, 1}));
    const std::string message = parseError(patched(labelsOf(R"(["Frontl_*"])")));
    EXPECT_NE(message.find("/transfer/labels/0/labels/0: no label name matches the pattern "
                           "\"Frontl_*\" (did you mean \"Frontal_L\"?)"),
              std::string::npos)
        << message;
}

TEST(FeatureScene, ProblemsNameTheirLocation) {
    EXPECT_NE(parseError(patched(peeler(R"({"mode": "segment", "labels": ["brain"]})") + "}"))
                  .find("/operators/0/alignment/labels: labels need a /labels section"),
              std::string::npos);
    EXPECT_NE(
        parseError(patched(R"({"labels": {"phantom": true},)" +
                           peeler(R"({"mode": "segment", "labels": ["brainn"]})").substr(1) + "}"))
            .find("/operators/0/alignment/labels/0: unknown label name \"brainn\" (did you "
                  "mean \"brain\"?)"),
        std::string::npos);
    EXPECT_NE(parseError(patched(peeler(R"({"mode": "segment"})") + "}"))
                  .find("/operators/0/alignment: segment alignment needs exactly one of "
                        "\"labels\" or \"range\", got neither"),
              std::string::npos);
    EXPECT_NE(parseError(patched(peeler(R"({"mode": "surface", "threshold": "auto"})") + "}"))
                  .find("/operators/0/alignment/threshold: expected a number or \"otsu\""),
              std::string::npos);
    EXPECT_NE(parseError(patched(peeler(R"({"mode": "surface", "depth": 0})") + "}"))
                  .find("/operators/0/alignment/depth: expected a number in (0, 10000]"),
              std::string::npos);
    EXPECT_NE(parseError(patched(peeler(R"({"mode": "axis", "band": 2})") + "}"))
                  .find("/operators/0/alignment/band: only with"),
              std::string::npos);
    EXPECT_NE(parseError(patched(R"({"labels": {"file": "labels.nii.gz", "phantom": true}})"))
                  .find("/labels: expected exactly one of \"file\" or \"phantom\", got both"),
              std::string::npos);
    EXPECT_NE(parseError(patched(R"({"labels": {"file": "labels.nii.gz"}})"))
                  .find("/labels/file: no such file"),
              std::string::npos);
    EXPECT_NE(parseError(patched(R"({"labels": {"phantom": true, "names": {"x": -1}}})"))
                  .find("/labels/names/x: expected an integer in [0, 2147483647]"),
              std::string::npos);
    EXPECT_NE(parseError(patched(R"({"transfer": {)" + std::string(kTransfer) +
                                 R"(, "labels": [{"labels": [1], )" + kTransfer + "}]}}"))
                  .find("/transfer/labels/0/labels: labels need a /labels section"),
              std::string::npos);
}

TEST(FeatureScene, PhantomLabelsNeedAPhantom) {
    json document = minimalScene();
    document["volume"] = {{"file", "scan.nrrd"}};
    document["labels"] = {{"phantom", true}};
    EXPECT_NE(parseError(document).find(
                  "/labels/phantom: the volume is not a phantom: give the label \"file\""),
              std::string::npos);
}

TEST(FeatureScene, SequentialCompositionAlignsOnlyTheLastOperator) {
    const std::string two = R"({"render": {"operator_composition": "sequential"},
        "operators": [
          {"type": "peeler", "placement": {"translate": [0, 0, 40], "scale": [40, 40, 20]},
           "alignment": {"mode": "surface"}},
          {"type": "peeler", "placement": {"translate": [0, 0, -40], "scale": [40, 40, 20]},
           "alignment": {"mode": "surface"}}]})";
    const std::string error = parseError(patched(two));
    EXPECT_NE(error.find("/operators/0/alignment/mode: under \"operator_composition\": "
                         "\"sequential\" only the last operator"),
              std::string::npos);
    EXPECT_EQ(error.find("/operators/1/"), std::string::npos) << error;
}

} // namespace
} // namespace cutaway::test
