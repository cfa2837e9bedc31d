#include "tests/support/complexes.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace tissuemesh::testing {

InterfaceComplex voxel_faces(const VoxelBlock& block)
{
    const std::array<std::size_t, 3> n{block.nx, block.ny, block.nz};
    InterfaceComplex complex;
    for (std::size_t k = 0; k <= n[2]; ++k)
        for (std::size_t j = 0; j <= n[1]; ++j)
            for (std::size_t i = 0; i <= n[0]; ++i)
                complex.vertices.push_back(block.origin_mm + block.size_mm * Vec3{double(i), double(j), double(k)});
    const auto lattice = [&](std::array<std::size_t, 3> p) {
        return static_cast<std::uint32_t>(p[0] + (n[0] + 1) * (p[1] + (n[1] + 1) * p[2]));
    };
    // Label of the voxel at cell c, the background outside the block.
    const auto label = [&](std::array<long, 3> c) -> Label {
        for (int a = 0; a < 3; ++a)
            if (c[a] < 0 || c[a] >= static_cast<long>(n[a])) return complex.background;
        return block.labels[std::size_t(c[0]) + n[0] * (std::size_t(c[1]) + n[1] * std::size_t(c[2]))];
    };
    // A face perpendicular to axis a at lattice plane p[a], between cell p - e_a (from) and cell p (to).
    for (int a = 0; a < 3; ++a) {
        const int b = (a + 1) % 3, d = (a + 2) % 3;
        std::array<std::size_t, 3> limit = n;
        limit[a] = n[a] + 1;
        for (std::size_t z = 0; z < limit[2]; ++z)
            for (std::size_t y = 0; y < limit[1]; ++y)
                for (std::size_t x = 0; x < limit[0]; ++x) {
                    const std::array<std::size_t, 3> p{x, y, z};
                    std::array<long, 3> cell{long(x), long(y), long(z)};
                    const Label to = label(cell);
                    --cell[a];
                    const Label from = label(cell);
                    if (from == to) continue;
                    // Corners in (a, b, d) order; (e_b x e_d) = e_a, so the normal points from `from` to `to`.
                    std::array<std::size_t, 3> q1 = p, q2 = p, q3 = p;
                    ++q1[b];
                    ++q2[b], ++q2[d];
                    ++q3[d];
                    complex.add_triangle({lattice(p), lattice(q1), lattice(q2)}, {from, to});
                    complex.add_triangle({lattice(p), lattice(q2), lattice(q3)}, {from, to});
                }
    }
    return complex;
}

void add_box(InterfaceComplex& complex, const Vec3& low, const Vec3& high, Label inside, Label outside)
{
    const auto base = static_cast<std::uint32_t>(complex.vertices.size());
    for (int corner = 0; corner < 8; ++corner)
        complex.vertices.push_back(
            {corner & 1 ? high[0] : low[0], corner & 2 ? high[1] : low[1], corner & 4 ? high[2] : low[2]});
    // Each face as a quad of corner bits, counter-clockwise seen from outside.
    const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& q : quads) {
        complex.add_triangle({base + q[0], base + q[1], base + q[2]}, {inside, outside});
        complex.add_triangle({base + q[0], base + q[2], base + q[3]}, {inside, outside});
    }
}

void add_tetrahedron(InterfaceComplex& complex, const Vec3& offset_mm, double size_mm, Label inside, Label outside)
{
    const auto base = static_cast<std::uint32_t>(complex.vertices.size());
    complex.vertices.push_back(offset_mm);
    complex.vertices.push_back(offset_mm + Vec3{size_mm, 0, 0});
    complex.vertices.push_back(offset_mm + Vec3{0, size_mm, 0});
    complex.vertices.push_back(offset_mm + Vec3{0, 0, size_mm});
    complex.add_triangle({base, base + 2, base + 1}, {inside, outside});
    complex.add_triangle({base, base + 1, base + 3}, {inside, outside});
    complex.add_triangle({base, base + 3, base + 2}, {inside, outside});
    complex.add_triangle({base + 1, base + 2, base + 3}, {inside, outside});
}

InterfaceComplex icosphere(int levels, double radius_mm, const Vec3& centre_mm)
{
    const double g = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<Vec3> unit{{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                           {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
    std::vector<Triangle> faces{{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                                {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (Vec3& v : unit) v = (1.0 / norm(v)) * v;
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
        const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const std::pair<std::uint32_t, std::uint32_t> key{std::min(a, b), std::max(a, b)};
            const auto found = midpoints.find(key);
            if (found != midpoints.end()) return found->second;
            const Vec3 m = unit[a] + unit[b];
            unit.push_back((1.0 / norm(m)) * m);
            return midpoints[key] = static_cast<std::uint32_t>(unit.size() - 1);
        };
        std::vector<Triangle> finer;
        finer.reserve(4 * faces.size());
        for (const Triangle& f : faces) {
            const std::uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
            finer.insert(finer.end(), {{f[0], ab, ca}, {f[1], bc, ab}, {f[2], ca, bc}, {ab, bc, ca}});
        }
        faces = std::move(finer);
    }
    InterfaceComplex complex;
    for (const Vec3& v : unit) complex.vertices.push_back(centre_mm + radius_mm * v);
    for (const Triangle& f : faces) complex.add_triangle(f, {1, 0});
    return complex;
}

void flip_triangle(InterfaceComplex& complex, std::size_t t)
{
    std::swap(complex.triangles[t][1], complex.triangles[t][2]);
}

std::uint32_t add_lone_triangle(InterfaceComplex& complex, const Vec3& a, const Vec3& b, const Vec3& c, LabelPair pair)
{
    const auto base = static_cast<std::uint32_t>(complex.vertices.size());
    complex.vertices.insert(complex.vertices.end(), {a, b, c});
    complex.add_triangle({base, base + 1, base + 2}, pair);
    return static_cast<std::uint32_t>(complex.triangles.size() - 1);
}

} // namespace tissuemesh::testing
