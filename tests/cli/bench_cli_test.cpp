// The Table 1 benchmark (bench/) on a tiny table, so it cannot rot unseen:
// every row it promises is in its records with consistent figures, the VTK
// comparison's spec matches the frames it timed, and a bad table is refused.
// Nothing here looks at a time's size: benchmarks report, tests never time.
#include "cli_util.hpp"

#include <future>
#include <nlohmann/json.hpp>

namespace cutaway::test {
namespace {

using nlohmann::json;

class BenchCli : public CliTest {
protected:
    void SetUp() override {
        if (std::string(CUTAWAY_BENCH).empty())
            GTEST_SKIP() << "configured without the benchmark (CUTAWAY_BUILD_BENCH=OFF)";
        CliTest::SetUp();
    }
    // A 24^3 head phantom with its labels and one peeler; the table gives it
    // all four rows.
    std::filesystem::path writeTable() {
        const json scene = {
            {"version", 1},
            {"volume", {{"phantom", "head"}, {"size", {24, 24, 24}}}},
            {"labels", {{"phantom", true}}},
            {"transfer",
             json::parse(R"({"points": [{"value": 0, "color": [1, 0.8, 0.7], "alpha": 0},
                 {"value": 255, "color": [1, 1, 1], "alpha": 0.8}]})")},
            {"camera", {{"orbit", {{"azimuth", 10}, {"elevation", 30}, {"distance", 90}}}}},
            {"operators",
             json::array({{{"type", "peeler"},
                           {"placement", {{"translate", {0, 0, 8}}, {"scale", {16, 16, 10}}}},
                           {"params", {{"hinge", -4}, {"thickness", 6}}}}})},
        };
        std::ofstream(m_dir / "tiny.json") << scene.dump();
        const json table = {
            {"datasets",
             {{{"dataset", "tiny"},
               {"scene", "tiny.json"},
               {"alignments",
                {{"none", nullptr},
                 {"axis", {{"mode", "axis"}}},
                 {"surface", {{"mode", "surface"}, {"threshold", "otsu"}, {"depth", 2}}},
                 {"segment", {{"mode", "segment"}, {"labels", {"brain"}}}}}}}}}};
        std::ofstream(m_dir / "table.json") << table.dump();
        return m_dir / "table.json";
    }
    struct BenchRun {
        CommandResult result;
        json records; ///< what it wrote to --json (null when it failed)
    };
    // The benchmark on the tiny table with `args`, its records written to `name`.
    BenchRun runBench(const std::string& name, const std::string& args) {
        const auto table = writeTable();
        const auto results = m_dir / name;
        BenchRun run{runProgram(CUTAWAY_BENCH, "--table " + table.string() + " --json " +
                                                   results.string() + " " + args),
                     {}};
        if (run.result.code == 0) std::ifstream(results) >> run.records;
        return run;
    }
    // A comparison script's table (ab_compare.py, ab_interleave.py): a ray-cast
    // row for "none" and "axis", each ending in `count` (its pairs or views).
    static void expectRowsCounting(const std::string& output, int count) {
        for (const char* alignment : {"none", "axis"}) {
            const std::string row = std::string("| tiny | ") + alignment + " | raycast | 1.0 | ";
            const auto at = output.find(row);
            ASSERT_NE(at, std::string::npos) << row << "\n" << output;
            const std::string line = output.substr(at, output.find('\n', at) - at);
            const std::string tail = " | " + std::to_string(count) + " |";
            EXPECT_EQ(line.substr(line.size() - tail.size()), tail) << line;
        }
    }
    // The script refuses a benchmark that is not an executable file, naming it.
    void expectRefusesAnAbsentBench(const std::string& script) {
        const CommandResult bad =
            runProgram("python3", script + " " + (m_dir / "absent").string() + " " + CUTAWAY_BENCH);
        EXPECT_EQ(bad.code, 2) << bad.output;
        EXPECT_NE(bad.output.find("absent: not an executable file"), std::string::npos)
            << bad.output;
    }
};

TEST_F(BenchCli, ATinyTableGivesARecordForEveryRowAndTheVtkSpec) {
    const auto vtk = m_dir / "vtk";
    const auto [r, records] =
        runBench("results.json", "--vtk-dir " + vtk.string() +
                                     " --frames 2 --spacings 1.0,0.5 --size 32 --turntable 2");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(r.output.find("vulkan validation"), std::string::npos) << r.output;
    int frames = 0, turntables = 0;
    for (const json& rec : records) {
        if (rec.value("kind", "") == "turntable") {
            ++turntables;
            EXPECT_EQ(rec["frames"], 2);
            EXPECT_EQ(rec["failed"], 0);
            // The steady rate leaves out the first frame's loading and bakes.
            EXPECT_GT(rec["first_frame_s"].get<double>(), 0.0);
            EXPECT_LT(rec["first_frame_s"].get<double>(), rec["total_s"].get<double>());
            // Single frames paired with it, just before and just after.
            EXPECT_GT(rec["single_fps_before"].get<double>(), 0.0);
            EXPECT_GT(rec["single_fps_after"].get<double>(), 0.0);
            // The steady rate counts the frames after the first over the time
            // from the first frame's files to the last's; the run's total also
            // holds what follows the last frame (closing writers, freeing).
            const double first = rec["first_frame_s"].get<double>();
            const double last = rec["last_frame_s"].get<double>();
            EXPECT_LT(first, last);
            EXPECT_LE(last, rec["total_s"].get<double>());
            EXPECT_NEAR(rec["steady_fps"].get<double>() * (last - first), 1.0, 1e-9);
            // Each compression's write, and the PNG's; uncompressed is the largest.
            const json& writes = rec["write_costs"];
            ASSERT_EQ(writes.size(), 6u) << writes.dump();
            for (const json& w : writes) {
                EXPECT_GT(w["ms_median"].get<double>(), 0.0) << w.dump();
                EXPECT_GT(w["bytes"].get<double>(), 0.0) << w.dump();
                if (w["file"].get<std::string>().ends_with(".exr")) {
                    EXPECT_LE(w["bytes"], writes[0]["bytes"]) << w.dump();
                }
            }
            EXPECT_EQ(writes[0]["file"], "frame_none.exr");
            // The views in turns, alone and with the previous frame's files.
            const json& turns = rec["interleaved"];
            EXPECT_EQ(turns["views"], 2);
            EXPECT_GT(turns["ms_alone"].get<double>(), 0.0);
            EXPECT_GT(turns["ms_with_files"].get<double>(), 0.0);
            continue;
        }
        ++frames;
        EXPECT_EQ(rec["dataset"], "tiny");
        EXPECT_EQ(rec["dims"], json({24, 24, 24}));
        EXPECT_EQ(rec["width"], 32);
        EXPECT_EQ(rec["frames"], 2);
        EXPECT_EQ(rec["operator"], rec["alignment"] == "none" ? "none" : "peeler");
        EXPECT_TRUE(rec["method"] == "raycast" || rec["method"] == "slicing") << rec.dump();
        EXPECT_LE(rec["ms_min"].get<double>(), rec["ms_median"].get<double>());
        EXPECT_LE(rec["ms_median"].get<double>(), rec["ms_max"].get<double>());
        EXPECT_NEAR(rec["fps"].get<double>() * rec["ms_median"].get<double>(), 1000.0, 1e-6);
        for (const char* bake :
             {"gradients_ms", "distance_field_ms", "field_ranges_ms", "segment_mask_ms",
              "segment_region_ms", "operator_map_ms", "value_spans_ms", "classify_ms"})
            EXPECT_TRUE(rec["bake_ms"][bake].is_number()) << bake;
        // The segment row's region covers the operator's box: some voxels,
        // none beyond the 24^3 grid.
        const json& region = rec["bake_ms"]["segment_region_voxels"];
        for (int a = 0; a < 3; ++a)
            EXPECT_TRUE(region[a] >= 1 && region[a] <= 24) << region.dump();
        EXPECT_GT(rec["peak_rss_mib"].get<double>(), 0.0);
        // One render of the row in a process of its own holds less than the
        // whole run, and the largest row's is the dataset's.
        const double one = rec["render_peak_rss_mib"].get<double>();
        EXPECT_GT(one, 10.0) << "at least the driver";
        EXPECT_LE(one, rec["render_peak_rss_mib_largest"].get<double>());
    }
    // none, axis, surface, segment: slicing and raycast; two spacings each.
    EXPECT_EQ(frames, 16);
    EXPECT_EQ(turntables, 1);
    json spec;
    std::ifstream(vtk / "vtk_tiny.json") >> spec;
    EXPECT_EQ(spec["cameras"].size(), 2u) << "one camera per timed no-operator frame at d = 1";
    EXPECT_EQ(std::filesystem::file_size(vtk / spec["raw"].get<std::string>()), 24u * 24 * 24 * 2);
}

TEST_F(BenchCli, WithoutBakeRepeatsOnlyTheFramesAreTimed) {
    // What vtk_bench.py runs just before and after VTK to pair the two.
    const auto [r, records] =
        runBench("paired.json", "--alignments none --methods raycast --spacings 1.0"
                                " --frames 1 --size 32 --turntable 0 --bake-repeats 0");
    ASSERT_EQ(r.code, 0) << r.output;
    ASSERT_EQ(records.size(), 1u) << records.dump();
    EXPECT_EQ(records[0]["method"], "raycast");
    EXPECT_GT(records[0]["ms_median"].get<double>(), 0.0);
    EXPECT_FALSE(records[0].contains("bake_ms"));
    EXPECT_FALSE(records[0].contains("render_peak_rss_mib")) << "no single-render processes";
}

TEST_F(BenchCli, TheCensusCountsTheRayCastRowsSamples) {
    const auto [r, records] =
        runBench("census.json", "--alignments none,axis --methods raycast,slicing --spacings 1.0"
                                " --frames 1 --size 32 --turntable 0 --bake-repeats 0 --census");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(r.output.find("vulkan validation"), std::string::npos) << r.output;
    ASSERT_EQ(records.size(), 4u) << records.dump();
    for (const json& rec : records) {
        SCOPED_TRACE(rec.dump());
        if (rec["method"] == "slicing") { // slicing has no rays to count
            EXPECT_FALSE(rec.contains("census"));
            continue;
        }
        const json& c = rec.at("census");
        EXPECT_GE(c.at("volume_fetched").get<double>(), c.at("volume_shaded").get<double>());
        EXPECT_GT(c.at("volume_shaded").get<double>(), 0.0);
        const double resolved = c.at("operator_resolved").get<double>();
        if (rec["alignment"] == "none")
            EXPECT_EQ(resolved, 0.0);
        else
            EXPECT_GT(resolved, 0.0);
    }
}

// bench/ab_compare.py, which judges a change by alternating two builds: the
// same build twice gives a row per alignment, each with its pairs counted.
TEST_F(BenchCli, AbCompareGivesEachRowItsRatioOverThePairs) {
    const auto table = writeTable();
    const std::string script = std::string(CUTAWAY_SOURCE_DIR) + "/bench/ab_compare.py";
    const CommandResult r =
        runProgram("python3", script + " " + CUTAWAY_BENCH + " " + CUTAWAY_BENCH + " --table " +
                                  table.string() +
                                  " --datasets '' --alignments none,axis --pairs 2 --frames 1"
                                  " --size 32");
    ASSERT_EQ(r.code, 0) << r.output;
    expectRowsCounting(r.output, 2);
    expectRefusesAnAbsentBench(script);
}

// Two benchmark processes taking turns (--baton, what bench/ab_interleave.py
// runs): both finish, and no frame of one overlaps a frame of the other,
// over two datasets (each runs in a child process of its own).
TEST_F(BenchCli, TwoProcessesTakingTurnsNeverRenderAtOnce) {
    json twice;
    std::ifstream(writeTable()) >> twice;
    json again = twice["datasets"][0];
    again["dataset"] = "again";
    twice["datasets"].push_back(again);
    const auto table = m_dir / "twice.json";
    std::ofstream(table) << twice.dump();
    const auto baton = m_dir / "baton";
    std::ofstream(baton) << "0\n";
    auto run = [&](int id) {
        return runProgram(CUTAWAY_BENCH,
                          "--table " + table.string() + " --json " +
                              (m_dir / ("turns" + std::to_string(id) + ".json")).string() +
                              " --baton " + baton.string() + " --baton-id " + std::to_string(id) +
                              " --baton-slice 0.005 --alignments none --methods raycast"
                              " --spacings 1.0 --frames 30 --size 64 --turntable 0"
                              " --bake-repeats 0");
    };
    auto second = std::async(std::launch::async, run, 1);
    const CommandResult first = run(0);
    const CommandResult other = second.get();
    ASSERT_EQ(first.code, 0) << first.output;
    ASSERT_EQ(other.code, 0) << other.output;
    std::vector<std::pair<double, double>> frames[2]; // [start, end] seconds
    for (int id = 0; id < 2; ++id) {
        json records;
        std::ifstream(m_dir / ("turns" + std::to_string(id) + ".json")) >> records;
        ASSERT_EQ(records.size(), 2u) << records.dump();
        for (const json& record : records) {
            const json& ms = record["frame_ms"];
            const json& starts = record["frame_start_s"];
            ASSERT_EQ(ms.size(), 30u);
            ASSERT_EQ(starts.size(), 30u);
            for (std::size_t i = 0; i < 30; ++i)
                frames[id].emplace_back(starts[i].get<double>(),
                                        starts[i].get<double>() + ms[i].get<double>() / 1000.0);
        }
    }
    for (const auto& [a0, a1] : frames[0])
        for (const auto& [b0, b1] : frames[1])
            EXPECT_TRUE(a1 <= b0 || b1 <= a0) << a0 << "-" << a1 << " and " << b0 << "-" << b1;
    // And they did take turns: in the order of their starts, the frames
    // change hands again and again (turns of 5 ms, frames of a few ms).
    std::vector<std::pair<double, int>> order;
    for (int id = 0; id < 2; ++id)
        for (const auto& f : frames[id])
            order.emplace_back(f.first, id);
    std::sort(order.begin(), order.end());
    int handovers = 0;
    for (std::size_t i = 1; i < order.size(); ++i)
        handovers += order[i].second != order[i - 1].second;
    EXPECT_GE(handovers, 4);
    // Both left their markers; without a baton no start is recorded.
    EXPECT_TRUE(std::filesystem::exists(baton.string() + ".done0"));
    EXPECT_TRUE(std::filesystem::exists(baton.string() + ".done1"));
    const auto [alone, records] =
        runBench("alone.json", "--alignments none --methods raycast --spacings 1.0 --frames 2"
                               " --size 32 --turntable 0 --bake-repeats 0");
    ASSERT_EQ(alone.code, 0) << alone.output;
    EXPECT_EQ(records[0]["frame_ms"].size(), 2u);
    EXPECT_FALSE(records[0].contains("frame_start_s"));
    const CommandResult bad = runProgram(CUTAWAY_BENCH, "--baton-id 2");
    EXPECT_NE(bad.code, 0);
    EXPECT_NE(bad.output.find("--baton-id"), std::string::npos) << bad.output;
}

// bench/ab_interleave.py: the same build twice gives a row per alignment,
// one paired view per frame.
TEST_F(BenchCli, AbInterleavePairsEveryView) {
    const auto table = writeTable();
    const std::string script = std::string(CUTAWAY_SOURCE_DIR) + "/bench/ab_interleave.py";
    const CommandResult r =
        runProgram("python3", script + " " + CUTAWAY_BENCH + " " + CUTAWAY_BENCH + " --table " +
                                  table.string() +
                                  " --dataset tiny --alignments none,axis --frames 3 --rounds 2"
                                  " --size 32 --slice 0.01");
    ASSERT_EQ(r.code, 0) << r.output;
    expectRowsCounting(r.output, 6);
    expectRefusesAnAbsentBench(script);
}

TEST_F(BenchCli, JitProfileFindsTheFrameInTheGeneratedCode) {
    for (const char* tool : {"perf", "gdb", "objdump"})
        if (runProgram("sh", std::string("-c 'command -v ") + tool + "'").code != 0)
            GTEST_SKIP() << tool << " is not installed (make bench installs it)";
    const auto table = writeTable();
    const std::string script = std::string(CUTAWAY_SOURCE_DIR) + "/bench/jit_profile.py";
    const CommandResult r = runProgram(
        "python3", script + " --bench " + CUTAWAY_BENCH + " --table " + table.string() +
                       " --dataset tiny --alignment none --size 512 --settle 1 --seconds 2");
    ASSERT_EQ(r.code, 0) << r.output;
    // "N samples, P % in generated code": a ray-cast frame is lavapipe's
    // generated code all but a few per cent, and the report names the
    // shader's own function.
    const auto at = r.output.find(" % in generated code");
    ASSERT_NE(at, std::string::npos) << r.output;
    const double share = std::stod(r.output.substr(r.output.rfind(' ', at - 1) + 1));
    EXPECT_GT(share, 50.0) << r.output;
    EXPECT_NE(r.output.find("the shader's own code"), std::string::npos) << r.output;
    const CommandResult bad =
        runProgram("python3", script + " --bench " + (m_dir / "absent").string());
    EXPECT_EQ(bad.code, 2) << bad.output;
    EXPECT_NE(bad.output.find("absent: not an executable file"), std::string::npos) << bad.output;
}

TEST_F(BenchCli, AMissingTableIsBadInputNamingIt) {
    const CommandResult r =
        runProgram(CUTAWAY_BENCH, "--table " + (m_dir / "absent.json").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("absent.json"), std::string::npos) << r.output;
}

} // namespace
} // namespace cutaway::test
