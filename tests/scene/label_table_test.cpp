// /labels/table: label tables in the forms atlases and tools ship
// (scene/label_table.hpp), their names used as /labels/names are, and
// "color": "table" colouring each label of a set in its table colour.
#include "core/error.hpp"
#include "scene/label_table.hpp"
#include "scene/scene.hpp"
#include "scene_test_util.hpp"

#include <cmath>
#include <gtest/gtest.h>

namespace cutaway::test {
namespace {

// The sRGB byte a linear channel encodes to (what a PNG of it holds).
int srgbByte(float linear) {
    const double c =
        linear <= 0.0031308 ? linear * 12.92 : 1.055 * std::pow(double(linear), 1.0 / 2.4) - 0.055;
    return int(std::lround(c * 255.0));
}

void expectColour(const LabelTable& t, std::int64_t id, int r, int g, int b) {
    ASSERT_TRUE(t.colors.count(id)) << "label " << id;
    const glm::vec3 c = t.colors.at(id);
    EXPECT_EQ(srgbByte(c.x), r);
    EXPECT_EQ(srgbByte(c.y), g);
    EXPECT_EQ(srgbByte(c.z), b);
}

// The same three labels in each format; names and colours read to the byte.
TEST(LabelTable, ReadsEachFormatToTheByte) {
    TempDir dir;
    const std::string freesurfer = "#$Id: FreeSurferColorLUT.txt\n"
                                   "#No. Label Name:                R   G   B   A\n\n"
                                   "0   Unknown                     0   0   0   0\n"
                                   "17  Left-Hippocampus            220 216 20  0\n"
                                   "1035 ctx-lh-insula              255 192 32  0\n";
    const std::string itksnap = "################################################\n"
                                "# ITK-SNAP Label Description File\n"
                                "#    IDX   -R-  -G-  -B-  -A--  VIS MSH  LABEL\n"
                                "    0     0    0    0        0  0  0    \"Clear Label\"\n"
                                "   17   220  216   20        1  1  1    \"Left Hippocampus\"\n"
                                " 1035   255  192   32      0.5  1  1    \"ctx-lh-insula # 2\"\n";
    const std::string slicer = "# Color table file /tmp/GenericColors.ctbl\n"
                               "# 3 values\n"
                               "0 background 0 0 0 0\n17 Left-Hippocampus 220 216 20 255\n"
                               "1035 ctx-lh-insula 255 192 32 255\n";
    const std::string plain =
        "0 background\n17 Left-Hippocampus\n1035 ctx-lh-insula extra columns\n";
    for (const auto& [name, text] : {std::pair{"FreeSurferColorLUT.txt", freesurfer},
                                     {"labels.txt", itksnap},
                                     {"GenericColors.ctbl", slicer},
                                     {"atlas.txt", plain}}) {
        SCOPED_TRACE(name);
        const LabelTable t = readLabelTable(dir.write(name, text));
        ASSERT_EQ(t.names.size(), 3u);
        EXPECT_EQ(
            t.names.at(std::string(name) == "labels.txt" ? "Left Hippocampus" : "Left-Hippocampus"),
            17);
        EXPECT_EQ(t.names.count(std::string(name) == "labels.txt" ? "ctx-lh-insula # 2"
                                                                  : "ctx-lh-insula"),
                  1u);
        if (std::string(name) == "atlas.txt") {
            EXPECT_TRUE(t.colors.empty()) << "a plain list gives no colours";
            continue;
        }
        expectColour(t, 17, 220, 216, 20);
        expectColour(t, 1035, 255, 192, 32);
    }
}

TEST(LabelTable, ALineOfNeitherFormIsAnErrorNamingItsLine) {
    TempDir dir;
    std::string message;
    try {
        readLabelTable(dir.write("bad.txt", "0 background\nseventeen hippocampus\n"));
    } catch (const InputError& e) {
        message = e.what();
    }
    EXPECT_NE(message.find("bad.txt:2: not a label line"), std::string::npos) << message;
}

// A colour outside [0, 255], an id named twice and a name given to two ids
// are errors naming the line (they were dropped or taken silently); the
// control: the same table with each fixed reads.
TEST(LabelTable, BadColoursAndRepeatedIdsOrNamesAreErrors) {
    TempDir dir;
    const auto messageOf = [&](const std::string& text) {
        try {
            readLabelTable(dir.write("t.txt", text));
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    std::string m = messageOf("0 background 0 0 0\n17 hippocampus 300 0 0\n");
    EXPECT_NE(m.find("t.txt:2: a colour outside [0, 255] for label 17"), std::string::npos) << m;
    m = messageOf("0 background\n17 hippocampus\n17 amygdala\n");
    EXPECT_NE(m.find("t.txt:3: label 17 again (first on line 2)"), std::string::npos) << m;
    m = messageOf("0 background\n17 hippocampus\n18 hippocampus\n");
    EXPECT_NE(m.find("t.txt:3: the name 'hippocampus' again (first on line 2)"), std::string::npos)
        << m;
    EXPECT_EQ(messageOf("0 background 0 0 0\n17 hippocampus 255 0 0\n18 amygdala\n"), "(no error)");
}

// "color": "auto": each label of the entry its own palette colour, by its
// rank among the entry's ids, with no table (an atlas with names only): 20
// labels take 20 distinct colours, the same colours on every parse; the
// 21st takes the first again. Control: "table" without a table is refused.
TEST(LabelTable, AutoColoursAreDistinctAndStable) {
    std::string ids;
    for (int id = 1; id <= 21; ++id)
        ids += (id > 1 ? ", " : "") + std::to_string(id * 3);
    const std::string points = R"([{"value": 0, "color": [1, 1, 1], "alpha": 0},
                                   {"value": 255, "color": [1, 1, 1], "alpha": 0.5}])";
    const auto scene = [&](const std::string& order) {
        return parseScene(patched(R"({"labels": {"phantom": true}, "transfer": {"points": )" +
                                  points + R"(, "labels": [{"labels": [)" + order +
                                  R"(], "color": "auto", "points": )" + points + "}]}}"),
                          "/nonexistent", "scene.json");
    };
    const Scene s = scene(ids);
    ASSERT_EQ(s.labelTransfers.size(), 21u);
    std::vector<glm::vec3> colours;
    for (std::size_t i = 0; i < 20; ++i) {
        EXPECT_EQ(s.labelTransfers[i].ids, std::vector<std::int64_t>{std::int64_t(3 * (i + 1))});
        const glm::vec3 c = s.labelTransfers[i].transfer.points[1].color;
        for (const glm::vec3& other : colours)
            EXPECT_GT(glm::length(c - other), 0.05f) << "label " << 3 * (i + 1);
        colours.push_back(c);
        EXPECT_EQ(s.labelTransfers[i].transfer.points[1].alpha, 0.5f) << "the points' opacity";
    }
    EXPECT_EQ(s.labelTransfers[20].transfer.points[1].color, colours[0]);
    const Scene shuffled = scene("63, 3, 30, 6, 9, 12, 15, 18, 21, 24, 27, 33, 36, 39, 42, 45, "
                                 "48, 51, 54, 57, 60");
    for (std::size_t i = 0; i < 21; ++i)
        EXPECT_EQ(shuffled.labelTransfers[i].transfer.points[1].color,
                  s.labelTransfers[i].transfer.points[1].color)
            << "the colour follows the id's rank, not the order written";
}

// The table's names work where names do; "color": "table" makes one
// transfer function per label, the points' opacities in its colour.
TEST(LabelTable, ASceneTakesItsNamesAndColours) {
    TempDir dir;
    dir.write("lut.txt",
              "1 Frontal_L 200 10 10 0\n2 Frontal_R 10 200 10 0\n3 Cerebellum 9 9 99 0\n");
    const std::string points = R"([{"value": 0, "color": [1, 1, 1], "alpha": 0},
                                   {"value": 255, "color": [1, 1, 1], "alpha": 0.5}])";
    const Scene scene = parseScene(
        patched(R"({"labels": {"phantom": true, "table": "lut.txt"}, "transfer": {"points": )" +
                points + R"(, "labels": [{"labels": ["Frontal_*"], "color": "table", "points": )" +
                points + R"(}, {"labels": ["Cerebellum"], "points": )" + points + "}]}}"),
        dir.path(), "scene.json");
    ASSERT_EQ(scene.labelTransfers.size(), 3u);
    EXPECT_EQ(scene.labelTransfers[0].ids, std::vector<std::int64_t>{1});
    EXPECT_EQ(scene.labelTransfers[1].ids, std::vector<std::int64_t>{2});
    EXPECT_EQ(srgbByte(scene.labelTransfers[0].transfer.points[1].color.x), 200);
    EXPECT_EQ(scene.labelTransfers[0].transfer.points[1].alpha, 0.5f);
    EXPECT_EQ(srgbByte(scene.labelTransfers[1].transfer.points[0].color.y), 200);
    EXPECT_EQ(scene.labelTransfers[2].transfer.points[1].color, glm::vec3(1.0f))
        << "control: a set without \"color\" keeps its points' colours";
    const std::string both = parseError(
        patched(R"({"labels": {"phantom": true, "table": "lut.txt", "names": {"a": 1}}})"),
        dir.path());
    EXPECT_NE(both.find("/labels: expected at most one of \"table\" or \"names\""),
              std::string::npos)
        << both;
    const std::string noTable =
        parseError(patched(R"({"labels": {"phantom": true}, "transfer": {"points": )" + points +
                           R"(, "labels": [{"labels": ["skull"], "color": "table", "points": )" +
                           points + "}]}}"),
                   dir.path());
    EXPECT_NE(noTable.find("/transfer/labels/0/color: \"table\" needs a /labels/table"),
              std::string::npos)
        << noTable;
}

} // namespace
} // namespace cutaway::test
