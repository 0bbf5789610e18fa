#pragma once
// Private helper: gzip/zlib streams over std::istream / std::ostream.
//
// GzipReader decompresses on demand, so callers decide how much output they
// accept: a reader that knows the declared data size reads exactly that much
// and then checks that nothing is left, which turns a gzip bomb into an error
// instead of memory exhaustion.
#include <cstddef>
#include <cstdint>
#include <istream>
#include <ostream>
#include <string>
#include <vector>
#include <zlib.h>

namespace cutaway::detail {

class GzipReader {
public:
    /// Reads compressed bytes from `in` at its current position. `context`
    /// (a file name) prefixes every error message.
    GzipReader(std::istream& in, std::string context);
    ~GzipReader();
    GzipReader(const GzipReader&) = delete;
    GzipReader& operator=(const GzipReader&) = delete;

    /// Decompresses up to `size` bytes into `dst`; returns fewer only at the
    /// end of the stream. Throws InputError on corrupt or truncated data.
    std::size_t read(std::byte* dst, std::size_t size);
    /// Decompresses and drops up to `size` bytes; returns how many were dropped.
    std::uint64_t skip(std::uint64_t size);
    /// Decompressed bytes produced so far.
    std::uint64_t position() const { return m_position; }

private:
    bool refill();

    std::istream& m_in;
    std::string m_context;
    z_stream m_stream{};
    std::vector<unsigned char> m_input;
    bool m_inputEnded = false;  ///< `in` has no more bytes
    bool m_streamEnded = false; ///< the last gzip member has ended
    std::uint64_t m_position = 0;
};

/// Reads up to `size` decompressed bytes into one buffer, reserved once at
/// `size` (the caller has checked it against the read budget) and filled a
/// chunk at a time: it never grows by copying, and its pages are touched
/// only as data arrives (a header that declares 8 GiB over a tiny stream
/// makes little resident). Peak: `size` plus a 1 MiB chunk.
std::vector<std::byte> readUpTo(GzipReader& reader, std::size_t size);

/// Writes `size` bytes as a gzip stream. Throws RuntimeError naming `context`
/// when the stream fails.
void writeGzip(std::ostream& out, const std::byte* data, std::size_t size,
               const std::string& context);

} // namespace cutaway::detail
