// MetaImage (.mha, .mhd): headers written here by hand, as ITK writes them,
// so the reader is checked against the format, not against a writer of ours.
#include "core/error.hpp"
#include "volume_test_util.hpp"

namespace cutaway::test {
namespace {

namespace fs = std::filesystem;

// 4 x 3 x 2 int16 voxels, value = 100 x + 10 y + z - 50 (x fastest).
std::vector<std::int16_t> mhaVoxels() {
    std::vector<std::int16_t> v;
    for (int z = 0; z < 2; ++z)
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 4; ++x)
                v.push_back(std::int16_t(100 * x + 10 * y + z - 50));
    return v;
}

std::string mhaBytes() {
    const std::vector<std::int16_t> v = mhaVoxels();
    return bytesOf(v.data(), v.size() * 2);
}

// ITK's header for the voxels above; `extra` lines go before ElementDataFile.
std::string mhaHeader(const std::string& extra, const std::string& dataFile = "LOCAL") {
    return "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
           "CompressedData = False\n"
           "TransformMatrix = 0 1 0 -1 0 0 0 0 1\nOffset = -10 20.5 3\n"
           "CenterOfRotation = 0 0 0\nAnatomicalOrientation = RAI\n"
           "ElementSpacing = 0.5 0.75 2\nDimSize = 4 3 2\nElementType = MET_SHORT\n" +
           extra + "ElementDataFile = " + dataFile + "\n";
}

std::string zlibOf(const std::string& data) {
    uLongf size = compressBound(uLong(data.size()));
    std::string out(size, '\0');
    compress2(reinterpret_cast<Bytef*>(out.data()), &size,
              reinterpret_cast<const Bytef*>(data.data()), uLong(data.size()), 6);
    out.resize(size);
    return out;
}

void expectMhaVoxels(const Volume& v) {
    ASSERT_EQ(v.dims, glm::ivec3(4, 3, 2));
    EXPECT_EQ(v.type, VoxelType::I16);
    const std::vector<std::int16_t> expected = mhaVoxels();
    for (std::size_t i = 0; i < expected.size(); ++i)
        ASSERT_EQ(v.value(i), expected[i]) << "voxel " << i;
}

class MetaImage : public VolumeFiles {};

// The voxels, and the geometry as ITK reads it: axis i's direction is the
// i-th triple of TransformMatrix (here x runs along +y, y along -x), the
// origin Offset, in LPS.
TEST_F(MetaImage, AnMhaReadsItsVoxelsAndGeometry) {
    const Volume v = readVolume(writeFile("a.mha", mhaHeader("") + mhaBytes()));
    expectMhaVoxels(v);
    EXPECT_EQ(v.spacing, glm::dvec3(0.5, 0.75, 2.0));
    EXPECT_EQ(v.origin, glm::dvec3(-10.0, 20.5, 3.0));
    EXPECT_EQ(v.direction[0], glm::dvec3(0, 1, 0));
    EXPECT_EQ(v.direction[1], glm::dvec3(-1, 0, 0));
    EXPECT_EQ(v.space, Space::LPS);
    EXPECT_EQ(v.physicalPosition(glm::dvec3(1, 0, 0)), glm::dvec3(-10.0, 21.0, 3.0));
}

std::string mhaBigEndian(std::string h) {
    return h.replace(h.find("BinaryDataByteOrderMSB = False"), 30, "BinaryDataByteOrderMSB = True");
}

std::span<const std::byte> mhaSpan(const std::string& text) {
    return {reinterpret_cast<const std::byte*>(text.data()), text.size()};
}

// A .mhd names its data file, here big endian after a 7-byte header of its own.
TEST_F(MetaImage, AnMhdReadsItsDataFileWithHeaderSizeAndByteOrder) {
    writeFile("a.raw", "garbage" + byteSwapped(mhaBytes(), 2));
    expectMhaVoxels(
        readVolume(writeFile("a.mhd", mhaBigEndian(mhaHeader("HeaderSize = 7\n", "a.raw")))));
    // HeaderSize -1: the data are the file's last bytes.
    expectMhaVoxels(
        readVolume(writeFile("b.mhd", mhaBigEndian(mhaHeader("HeaderSize = -1\n", "a.raw")))));
    // Control: read little endian, the same bytes are other numbers.
    const Volume swapped = readVolume(writeFile("c.mhd", mhaHeader("HeaderSize = 7\n", "a.raw")));
    EXPECT_NE(swapped.value(1), mhaVoxels()[1]);
}

// The files a run reads, as output paths are checked against them: a .mhd
// and the data file it names; a .mha with LOCAL data alone.
TEST_F(MetaImage, TheFilesAnMhdReadsIncludeItsDataFile) {
    writeFile("d.raw", mhaBytes());
    const fs::path mhd = writeFile("d.mhd", mhaHeader("", "d.raw"));
    EXPECT_EQ(volumeFiles(mhd), (std::vector<fs::path>{mhd, path("d.raw")}));
    const fs::path mha = writeFile("d.mha", mhaHeader("", "LOCAL") + mhaBytes());
    EXPECT_EQ(volumeFiles(mha), std::vector<fs::path>{mha});
    // A header that cannot be read gives the file alone.
    const fs::path bad = writeFile("bad.mhd", "not a header\n");
    EXPECT_EQ(volumeFiles(bad), std::vector<fs::path>{bad});
}

TEST_F(MetaImage, CompressedDataIsZlib) {
    const std::string packed = zlibOf(mhaBytes());
    std::string h = mhaHeader("CompressedDataSize = " + std::to_string(packed.size()) + "\n");
    h.replace(h.find("CompressedData = False"), 22, "CompressedData = True");
    expectMhaVoxels(readVolume(writeFile("c.mha", h + packed)));
    const std::string text = h + packed;
    expectMhaVoxels(readMetaImageBytes(mhaSpan(text), "c.mha"));
}

TEST_F(MetaImage, ATwoDimensionalImageIsOneSlice) {
    const std::string h = "NDims = 2\nDimSize = 4 3\nElementSpacing = 0.5 0.75\n"
                          "ElementType = MET_UCHAR\nElementDataFile = LOCAL\n";
    const Volume v = readVolume(writeFile("d.mha", h + std::string(12, '\x07')));
    EXPECT_EQ(v.dims, glm::ivec3(4, 3, 1));
    EXPECT_EQ(v.value(11), 7.0);
    EXPECT_EQ(v.space, Space::None);
}

// What is not read says what and where; a wrong header never reads garbage.
TEST_F(MetaImage, RefusalsNameTheFileAndTheField) {
    const auto refused = [&](const std::string& name, const std::string& text,
                             const std::string& expected) {
        SCOPED_TRACE(name);
        const auto path = writeFile(name, text);
        const std::string message = inputError([&] { readVolume(path); });
        EXPECT_NE(message.find(path.string() + ": "), std::string::npos) << message;
        EXPECT_NE(message.find(expected), std::string::npos) << message;
    };
    const std::string data = mhaBytes();
    refused("short.mha", mhaHeader("") + data.substr(0, 30), "data truncated");
    refused(
        "ascii.mha",
        mhaHeader("").replace(mhaHeader("").find("BinaryData = True"), 17, "BinaryData = False") +
            data,
        "ASCII");
    refused("rgb.mha", mhaHeader("ElementNumberOfChannels = 3\n") + data, "3 channels");
    refused("list.mhd", mhaHeader("", "LIST"), "several files");
    refused("type.mha",
            mhaHeader("").replace(mhaHeader("").find("MET_SHORT"), 9, "MET_LONG_LONG") + data,
            "ElementType 'MET_LONG_LONG'");
    refused("four.mha",
            "NDims = 4\n" + mhaHeader("").substr(mhaHeader("").find("BinaryData")) + data,
            "NDims must be 2 or 3");
    refused("nodata.mha", "NDims = 3\nDimSize = 4 3 2\n", "without ElementDataFile");
    refused("dims.mha", mhaHeader("").replace(mhaHeader("").find("4 3 2"), 5, "4 x 2") + data,
            "DimSize: 'x' is not a finite number");
    refused("huge.mha", mhaHeader("").replace(mhaHeader("").find("4 3 2"), 5, "4e5 4e5 4e5") + data,
            "volume too large");
    refused("missing.mhd", mhaHeader("", "absent.raw"), "absent.raw");
    const auto withMatrix = [&](const std::string& matrix) {
        std::string h = mhaHeader("");
        return h.replace(h.find("0 1 0 -1 0 0 0 0 1"), 18, matrix) + data;
    };
    refused("singular.mha", withMatrix("1 0 0 1 0 0 0 0 1"), "TransformMatrix is singular");
    refused("flat.mha", withMatrix("1 0 0 0 0 0 0 0 1"), "axis 1's direction has length 0");
    // Control: a matrix of scaled axes is made unit length, not refused.
    const Volume scaled = readVolume(writeFile("scaled.mha", withMatrix("0 2 0 -2 0 0 0 0 2")));
    EXPECT_NEAR(scaled.direction[0][1], 1.0, 1e-12);
    EXPECT_NEAR(scaled.direction[1][0], -1.0, 1e-12);
}

// Bytes this process has read through read() so far (/proc/self/io).
std::uint64_t bytesRead() {
    std::ifstream io("/proc/self/io");
    std::string key;
    std::uint64_t value = 0;
    while (io >> key >> value)
        if (key == "rchar:") return value;
    return 0;
}

// A header line that never ends (a 256 MiB sparse file of "NDims = 3" and
// zeros) is refused having read the header's 64 KiB, not the file: the
// line was read whole before the cap was checked (20 GB: 4 GB of memory).
TEST_F(MetaImage, AHeaderLineThatNeverEndsIsRefusedAtTheCap) {
    const auto path = writeFile("endless.mha", "NDims = 3 ");
    std::filesystem::resize_file(path, std::uint64_t{256} << 20);
    const std::uint64_t before = bytesRead();
    const std::string message = inputError([&] { readVolume(path); });
    const std::uint64_t read = bytesRead() - before;
    EXPECT_NE(message.find("no ElementDataFile within the first 64 KiB"), std::string::npos)
        << message;
    EXPECT_LT(read, std::uint64_t{4} << 20) << "bytes read of a 256 MiB file";
    EXPECT_GT(read, std::uint64_t{64} << 10) << "control: the header's cap was read";
}

// Text a header quotes in a message has its control characters escaped, so
// a file cannot put a terminal escape sequence on the screen.
TEST_F(MetaImage, QuotedHeaderTextIsEscaped) {
    const auto path = writeFile("escape.mha", "NDims = 3\n\x1b]0;owned\x07 no equals sign\n");
    const std::string message = inputError([&] { readVolume(path); });
    EXPECT_EQ(message.find('\x1b'), std::string::npos) << message;
    EXPECT_NE(message.find("'\\x1b]0;owned\\x07 no equals sign'"), std::string::npos) << message;
}

} // namespace
} // namespace cutaway::test
