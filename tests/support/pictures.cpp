#include "tests/support/pictures.h"

#include <cmath>

#include "core/atomic_file.h"
#include "render/png.h"

namespace tissuemesh::testing {

std::size_t count_shaded(const render::Canvas& picture, const render::Rgb& colour, double min_shade)
{
    const double norm2 = double(colour[0]) * colour[0] + double(colour[1]) * colour[1] + double(colour[2]) * colour[2];
    std::size_t count = 0;
    for (const render::Rgb& p : picture.pixels()) {
        // Least-squares shade of p along the colour, then every channel within rounding of it.
        const double s = (double(p[0]) * colour[0] + double(p[1]) * colour[1] + double(p[2]) * colour[2]) / norm2;
        if (s < min_shade || s > 1.0 + 1e-9) continue;
        bool close = true;
        for (int c = 0; c < 3; ++c) close = close && std::abs(double(p[c]) - s * colour[c]) <= 3;
        count += close;
    }
    return count;
}

std::size_t count_exact(const render::Canvas& picture, const render::Rgb& colour)
{
    std::size_t count = 0;
    for (const render::Rgb& p : picture.pixels()) count += p == colour;
    return count;
}

render::Canvas read_png(const std::filesystem::path& path)
{
    return render::decode_png(read_file_bytes(path), path.string());
}

} // namespace tissuemesh::testing
