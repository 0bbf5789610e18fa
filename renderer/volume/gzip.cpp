#include "volume/gzip.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <climits>

namespace cutaway::detail {

namespace {

constexpr std::size_t kInputChunk = std::size_t{1} << 18; // 256 KiB of compressed input
constexpr std::size_t kReadChunk = std::size_t{1} << 20;  // readUpTo's chunk

std::string zlibMessage(const z_stream& stream, int code) {
    if (stream.msg != nullptr) return stream.msg;
    return "zlib error " + std::to_string(code);
}

} // namespace

GzipReader::GzipReader(std::istream& in, std::string context)
    : m_in(in), m_context(std::move(context)), m_input(kInputChunk) {
    // 15 + 32: the largest window, with automatic gzip or zlib header detection.
    const int code = inflateInit2(&m_stream, 15 + 32);
    if (code != Z_OK) {
        throw RuntimeError(m_context + ": cannot start gzip decompression (" +
                           zlibMessage(m_stream, code) + ")");
    }
}

GzipReader::~GzipReader() {
    inflateEnd(&m_stream);
}

bool GzipReader::refill() {
    if (m_inputEnded) return false;
    m_in.read(reinterpret_cast<char*>(m_input.data()),
              static_cast<std::streamsize>(m_input.size()));
    const auto got = static_cast<std::size_t>(m_in.gcount());
    if (got < m_input.size()) m_inputEnded = true;
    m_stream.next_in = m_input.data();
    m_stream.avail_in = static_cast<uInt>(got);
    return got > 0;
}

std::size_t GzipReader::read(std::byte* dst, std::size_t size) {
    std::size_t produced = 0;
    while (produced < size && !m_streamEnded) {
        if (m_stream.avail_in == 0 && !refill()) {
            if (m_position == 0 && m_stream.total_in == 0) {
                throw InputError(m_context + ": gzip data is empty");
            }
            throw InputError(m_context + ": gzip stream truncated (it ends after " +
                             std::to_string(m_position) + " decompressed bytes)");
        }
        const auto room = static_cast<uInt>(std::min<std::size_t>(size - produced, UINT_MAX));
        m_stream.next_out = reinterpret_cast<Bytef*>(dst + produced);
        m_stream.avail_out = room;
        const int code = inflate(&m_stream, Z_NO_FLUSH);
        const std::size_t made = room - m_stream.avail_out;
        produced += made;
        m_position += made;
        if (code == Z_STREAM_END) {
            // Concatenated gzip members form one stream (as gzip -d reads them);
            // any other trailing bytes are ignored, as gzip does with padding.
            if (m_stream.avail_in == 0) refill();
            if (m_stream.avail_in > 0 && m_stream.next_in[0] == 0x1f) {
                inflateReset(&m_stream);
            } else {
                m_streamEnded = true;
            }
        } else if (code == Z_BUF_ERROR) {
            // No progress: more input is needed; the loop refills or reports truncation.
            if (m_stream.avail_in != 0) {
                throw InputError(m_context + ": corrupt gzip data (decompression stalled)");
            }
        } else if (code != Z_OK) {
            throw InputError(m_context + ": corrupt gzip data (" + zlibMessage(m_stream, code) +
                             ")");
        }
    }
    return produced;
}

std::uint64_t GzipReader::skip(std::uint64_t size) {
    std::vector<std::byte> scratch(std::min<std::uint64_t>(size, std::uint64_t{1} << 20));
    std::uint64_t done = 0;
    while (done < size) {
        const auto want =
            static_cast<std::size_t>(std::min<std::uint64_t>(size - done, scratch.size()));
        const std::size_t got = read(scratch.data(), want);
        done += got;
        if (got < want) break;
    }
    return done;
}

std::vector<std::byte> readUpTo(GzipReader& reader, std::size_t size) {
    std::vector<std::byte> data;
    data.reserve(size); // mapped, not touched: pages come as they are written
    std::vector<std::byte> chunk(std::min<std::size_t>(size, kReadChunk));
    while (data.size() < size) {
        const std::size_t got =
            reader.read(chunk.data(), std::min(chunk.size(), size - data.size()));
        data.insert(data.end(), chunk.begin(), chunk.begin() + std::ptrdiff_t(got));
        if (got == 0) break;
    }
    return data;
}

void writeGzip(std::ostream& out, const std::byte* data, std::size_t size,
               const std::string& context) {
    z_stream stream{};
    // 15 + 16: the largest window with a gzip header; level 6 balances size and
    // speed (a 256^3 volume compresses in well under a second).
    int code = deflateInit2(&stream, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY);
    if (code != Z_OK) {
        throw RuntimeError(context + ": cannot start gzip compression (" +
                           zlibMessage(stream, code) + ")");
    }
    std::vector<unsigned char> buffer(kInputChunk);
    std::size_t consumed = 0;
    do {
        const std::size_t chunk = std::min<std::size_t>(size - consumed, UINT_MAX / 2);
        stream.next_in = reinterpret_cast<Bytef*>(const_cast<std::byte*>(data + consumed));
        stream.avail_in = static_cast<uInt>(chunk);
        consumed += chunk;
        const int flush = consumed == size ? Z_FINISH : Z_NO_FLUSH;
        do {
            stream.next_out = buffer.data();
            stream.avail_out = static_cast<uInt>(buffer.size());
            code = deflate(&stream, flush);
            if (code == Z_STREAM_ERROR) {
                deflateEnd(&stream);
                throw RuntimeError(context + ": gzip compression failed");
            }
            const std::size_t made = buffer.size() - stream.avail_out;
            out.write(reinterpret_cast<const char*>(buffer.data()),
                      static_cast<std::streamsize>(made));
        } while (stream.avail_out == 0);
    } while (consumed < size);
    deflateEnd(&stream);
    if (code != Z_STREAM_END || !out) {
        throw RuntimeError(context + ": writing gzip data failed");
    }
}

} // namespace cutaway::detail
