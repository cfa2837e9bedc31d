// Initial surfaces for snakes (declared in surface/snake.h).
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "core/error.h"
#include "surface/snake.h"

namespace tissuemesh::surface {

InterfaceComplex ellipsoid_surface(const Vec3& centre_mm, const Vec3& radii_mm, double edge_mm, LabelPair pair)
{
    for (const double r : radii_mm)
        if (!(r > 0) || !std::isfinite(r))
            throw InputError(concat("snake: ellipsoid radius ", r, " mm must be a positive number"));
    if (!(edge_mm > 0) || !std::isfinite(edge_mm))
        throw InputError(concat("snake: edge length ", edge_mm, " mm must be a positive number"));
    // The icosahedron's 12 vertices are the cyclic permutations of (0, +-1, +-phi).
    const double phi = (1 + std::sqrt(5.0)) / 2;
    std::vector<Vec3> unit;
    for (int s1 = -1; s1 <= 1; s1 += 2)
        for (int s2 = -1; s2 <= 1; s2 += 2) {
            const double a = s1, b = s2 * phi;
            unit.push_back({0, a, b});
            unit.push_back({a, b, 0});
            unit.push_back({b, 0, a});
        }
    for (Vec3& v : unit) v = (1 / norm(v)) * v;
    // Faces: the 20 triples of mutually adjacent vertices (edge length 2 before normalising), made outward.
    std::vector<Triangle> faces;
    double shortest = 1e300;
    for (std::size_t a = 0; a < 12; ++a)
        for (std::size_t b = a + 1; b < 12; ++b) shortest = std::min(shortest, distance(unit[a], unit[b]));
    const auto adjacent = [&](std::size_t a, std::size_t b) { return distance(unit[a], unit[b]) < 1.01 * shortest; };
    for (std::uint32_t a = 0; a < 12; ++a)
        for (std::uint32_t b = a + 1; b < 12; ++b)
            for (std::uint32_t c = b + 1; c < 12; ++c) {
                if (!adjacent(a, b) || !adjacent(b, c) || !adjacent(a, c)) continue;
                const bool outward = dot(cross(unit[b] - unit[a], unit[c] - unit[a]), unit[a]) > 0;
                faces.push_back(outward ? Triangle{a, b, c} : Triangle{a, c, b});
            }
    // Halve every edge until the longest stretched edge is near the target.
    const double largest = std::max({radii_mm[0], radii_mm[1], radii_mm[2]});
    double current = shortest * largest;
    for (int level = 0; current > 1.3 * edge_mm && level < 8; ++level, current /= 2) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middle;
        const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::minmax(a, b);
            const auto [it, added] =
                middle.try_emplace({key.first, key.second}, static_cast<std::uint32_t>(unit.size()));
            if (added) {
                const Vec3 m = unit[a] + unit[b];
                unit.push_back((1 / norm(m)) * m);
            }
            return it->second;
        };
        std::vector<Triangle> finer;
        finer.reserve(4 * faces.size());
        for (const Triangle& f : faces) {
            const std::uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
            finer.insert(finer.end(), {Triangle{f[0], ab, ca}, Triangle{ab, f[1], bc}, Triangle{ca, bc, f[2]},
                                       Triangle{ab, bc, ca}});
        }
        faces = std::move(finer);
    }
    InterfaceComplex complex;
    for (const Vec3& u : unit)
        complex.vertices.push_back(centre_mm + Vec3{radii_mm[0] * u[0], radii_mm[1] * u[1], radii_mm[2] * u[2]});
    for (const Triangle& f : faces) complex.add_triangle(f, pair);
    return complex;
}

std::vector<SnakeTarget> nested_label_targets(const LabelImage& image, const std::vector<Label>& tissues_outer_first,
                                              double sigma_mm)
{
    std::vector<SnakeTarget> targets;
    for (std::size_t k = 0; k < tissues_outer_first.size(); ++k) {
        const Label tissue = tissues_outer_first[k];
        if (tissue == 0)
            throw InputError("snake: the background (label 0) cannot be a snake's tissue; list the tissues inside it");
        for (std::size_t j = 0; j < k; ++j)
            if (tissues_outer_first[j] == tissue)
                throw InputError(concat("snake: tissue ", image.name_of(tissue),
                                        " is listed twice; list each once, "
                                        "outermost first"));
        const Label outside = k == 0 ? Label{0} : tissues_outer_first[k - 1];
        targets.push_back({{tissue, outside}, label_potential(image, enclosed_region(image, tissue), sigma_mm)});
    }
    return targets;
}

InterfaceComplex bounding_ellipsoids(const std::vector<SnakeTarget>& targets, double scale, double edge_mm)
{
    if (!(scale > 0) || !std::isfinite(scale))
        throw InputError(concat("snake: start scale ", scale, " must be a positive number; try 1.15"));
    InterfaceComplex complex;
    for (const SnakeTarget& target : targets) {
        const auto bounds = target.field.positive_bounds_mm();
        if (!bounds)
            throw InputError(concat("snake: the field of snake ", target.pair.from, "|", target.pair.to,
                                    " is nowhere positive: nothing to surround; check the tissue or the iso value"));
        const Vec3 centre = 0.5 * ((*bounds)[0] + (*bounds)[1]);
        const double half_voxel = 0.5 * target.field.smallest_spacing_mm();
        Vec3 radii{0, 0, 0};
        for (std::size_t a = 0; a < 3; ++a) radii[a] = scale * 0.5 * ((*bounds)[1][a] - (*bounds)[0][a]) + half_voxel;
        append_complex(complex, ellipsoid_surface(centre, radii, edge_mm, target.pair));
    }
    return complex;
}

void label_start_surface(InterfaceComplex& complex, const std::vector<SnakeTarget>& targets, const std::string& what)
{
    const auto matches = [&](const LabelPair& side) {
        for (const SnakeTarget& t : targets)
            if (side == t.pair || (side.from == t.pair.to && side.to == t.pair.from)) return true;
        return false;
    };
    if (std::all_of(complex.sides.begin(), complex.sides.end(), matches)) return;
    const bool one_pair =
        !complex.sides.empty() && std::all_of(complex.sides.begin(), complex.sides.end(),
                                              [&](const LabelPair& side) { return side == complex.sides.front(); });
    if (targets.size() == 1 && one_pair) {
        for (LabelPair& side : complex.sides) side = targets.front().pair;
        return;
    }
    throw InputError(concat(what, ": the start surface's tissue pairs do not match the snakes (one pair per "
                                  "snake, outermost against the background); label it as tm-snake writes them"));
}

void append_complex(InterfaceComplex& complex, const InterfaceComplex& part)
{
    const auto offset = static_cast<std::uint32_t>(complex.vertices.size());
    complex.vertices.insert(complex.vertices.end(), part.vertices.begin(), part.vertices.end());
    for (std::size_t t = 0; t < part.triangle_count(); ++t) {
        const Triangle& f = part.triangles[t];
        complex.add_triangle({f[0] + offset, f[1] + offset, f[2] + offset}, part.sides[t]);
    }
    for (const auto& [label, name] : part.names) complex.names.emplace(label, name);
}

} // namespace tissuemesh::surface
