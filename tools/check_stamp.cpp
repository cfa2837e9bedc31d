#include "tools/check_stamp.h"

#include <bit>
#include <cstdint>
#include <cstdio>
#include <fstream>

#include "core/atomic_file.h"
#include "core/error.h"

namespace tissuemesh::tools {
namespace {

constexpr const char* stamp_word = "tissuemesh-checked";

/// A 64-bit digest fed word by word (multiply and xor-shift mixing): not cryptographic, but any change to
/// the complex changes it with a probability of 1 - 2^-64.
class Digest {
public:
    void add(std::uint64_t word)
    {
        state_ = (state_ ^ word) * 0x9e3779b97f4a7c15ull;
        state_ ^= state_ >> 29;
    }
    std::uint64_t value() const { return state_; }

private:
    std::uint64_t state_ = 0xcbf29ce484222325ull;
};

} // namespace

std::string check_stamp(const InterfaceComplex& complex)
{
    Digest digest;
    digest.add(complex.background);
    digest.add(complex.vertices.size());
    for (const Vec3& v : complex.vertices)
        for (const double c : v) digest.add(std::bit_cast<std::uint64_t>(c));
    digest.add(complex.triangles.size());
    for (std::size_t t = 0; t < complex.triangles.size(); ++t) {
        const Triangle& tri = complex.triangles[t];
        digest.add(tri[0] | std::uint64_t{tri[1]} << 32);
        digest.add(tri[2] | std::uint64_t{complex.sides[t].from} << 32 | std::uint64_t{complex.sides[t].to} << 48);
    }
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(digest.value()));
    return concat(stamp_word, ' ', TM_VERSION, ' ', hex);
}

std::string read_check_stamp(const std::string& path)
{
    if (full_extension(path) != ".ply") return "";
    std::ifstream in(path, std::ios::binary);
    const std::string prefix = concat("comment ", stamp_word, ' ');
    std::string line;
    // The header is a few hundred bytes of text lines; the binary data starts after end_header.
    for (int lines = 0; lines < 1000 && std::getline(in, line) && line != "end_header"; ++lines)
        if (line.rfind(prefix, 0) == 0) return line.substr(8);
    return "";
}

} // namespace tissuemesh::tools
