#include "volume/detail/tetgen_adapter.h"

#include <cstdint>
#include <cstring>
#include <mutex>

#include <tetgen.h>

#include "core/error.h"
#include "volume/detail/isolated_call.h"

namespace tissuemesh::volume::detail {
namespace {

std::string explain_code(int code)
{
    switch (code) {
    case 1: return "TetGen ran out of memory";
    case 2: return "TetGen hit an internal error";
    case 3: return "TetGen found intersecting input facets";
    case 4: return "TetGen found a very small input feature (facets or vertices nearly touching)";
    case 5: return "TetGen found two nearly coplanar, very close facets";
    case 10: return "TetGen rejected the input (duplicate or degenerate facets)";
    default: return concat("TetGen failed with code ", code);
    }
}

void fill_input(const TetgenInput& input, tetgenio& in)
{
    in.firstnumber = 0;
    in.numberofpoints = static_cast<int>(input.points.size() / 3);
    in.pointlist = new REAL[input.points.size()];
    std::copy(input.points.begin(), input.points.end(), in.pointlist);

    in.numberoffacets = static_cast<int>(input.triangles.size());
    in.facetlist = new tetgenio::facet[input.triangles.size()];
    in.facetmarkerlist = new int[input.triangles.size()];
    for (std::size_t t = 0; t < input.triangles.size(); ++t) {
        tetgenio::facet& facet = in.facetlist[t];
        tetgenio::init(&facet);
        facet.numberofpolygons = 1;
        facet.polygonlist = new tetgenio::polygon[1];
        tetgenio::init(&facet.polygonlist[0]);
        facet.polygonlist[0].numberofvertices = 3;
        facet.polygonlist[0].vertexlist = new int[3];
        for (int c = 0; c < 3; ++c) facet.polygonlist[0].vertexlist[c] = input.triangles[t][c];
        in.facetmarkerlist[t] = static_cast<int>(t) + 1;
    }
    in.numberofregions = static_cast<int>(input.regions.size());
    if (!input.regions.empty()) {
        in.regionlist = new REAL[5 * input.regions.size()];
        for (std::size_t r = 0; r < input.regions.size(); ++r) {
            for (int c = 0; c < 3; ++c) in.regionlist[5 * r + c] = input.regions[r].seed[c];
            in.regionlist[5 * r + 3] = input.regions[r].attribute;
            in.regionlist[5 * r + 4] = input.regions[r].max_volume;
        }
    }
}

/// TetGen's output in a flat byte string: five counts, then the arrays as they are in memory (the
/// child process that ran TetGen and the parent reading it are the same program).
class OutputBytes {
public:
    static std::string pack(const tetgenio& out)
    {
        OutputBytes bytes;
        const auto points = static_cast<std::uint64_t>(out.numberofpoints);
        const auto tets = static_cast<std::uint64_t>(out.numberoftetrahedra);
        const auto faces = static_cast<std::uint64_t>(out.numberoftrifaces);
        const std::uint64_t attributes = out.numberoftetrahedronattributes > 0 ? tets : 0;
        const std::uint64_t markers = out.trifacemarkerlist != nullptr ? faces : 0;
        for (const std::uint64_t count : {points, tets, attributes, faces, markers}) bytes.put(&count, 1);
        bytes.put(out.pointlist, 3 * points);
        for (std::uint64_t t = 0; t < tets; ++t)
            bytes.put(out.tetrahedronlist + t * static_cast<std::uint64_t>(out.numberofcorners), 4);
        for (std::uint64_t t = 0; t < attributes; ++t)
            bytes.put(out.tetrahedronattributelist + t * static_cast<std::uint64_t>(out.numberoftetrahedronattributes),
                      1);
        bytes.put(out.trifacelist, 3 * faces);
        bytes.put(out.trifacemarkerlist, markers);
        return std::move(bytes.text_);
    }

    static TetgenOutput unpack(std::string text)
    {
        OutputBytes bytes;
        bytes.text_ = std::move(text);
        std::uint64_t counts[5];
        for (std::uint64_t& count : counts) bytes.get(&count, 1);
        TetgenOutput result;
        result.points.resize(3 * counts[0]);
        result.tets.resize(counts[1]);
        result.tet_attributes.resize(counts[2]);
        result.faces.resize(counts[3]);
        result.face_markers.resize(counts[3], 0);
        bytes.get(result.points.data(), result.points.size());
        bytes.get(result.tets.data(), result.tets.size());
        bytes.get(result.tet_attributes.data(), counts[2]);
        bytes.get(result.faces.data(), result.faces.size());
        bytes.get(result.face_markers.data(), counts[4]);
        if (bytes.offset_ != bytes.text_.size())
            throw AlgorithmError("TetGen's result came back incomplete from its process");
        return result;
    }

private:
    template <typename T>
    void put(const T* values, std::uint64_t count)
    {
        if (count == 0) return; // TetGen leaves the lists it did not fill null
        text_.append(reinterpret_cast<const char*>(values), count * sizeof(T));
    }
    template <typename T>
    void get(T* values, std::uint64_t count)
    {
        const std::uint64_t size = count * sizeof(T);
        if (size == 0) return;
        if (size > text_.size() - offset_)
            throw AlgorithmError("TetGen's result came back incomplete from its process");
        std::memcpy(values, text_.data() + offset_, size);
        offset_ += size;
    }

    std::string text_;
    std::size_t offset_ = 0;
};

static_assert(sizeof(std::array<int, 4>) == 4 * sizeof(int) && sizeof(std::array<int, 3>) == 3 * sizeof(int));

} // namespace

int exact_side(const std::array<double, 3>& a, const std::array<double, 3>& b, const std::array<double, 3>& c,
               const std::array<double, 3>& d)
{
    // The predicates need their rounding constants once; their static filter (sized by the bounding box,
    // which this function does not know) stays off, the adaptive stages keep them exact.
    static std::once_flag once;
    std::call_once(once, [] { exactinit(0, 0, 1, 1.0, 1.0, 1.0); });
    std::array<double, 3> pa = a, pb = b, pc = c, pd = d;
    // Shewchuk's orient3d is positive when d lies below the plane of a counter-clockwise (a, b, c).
    const double orientation = orient3d(pa.data(), pb.data(), pc.data(), pd.data());
    return orientation < 0 ? 1 : orientation > 0 ? -1 : 0;
}

TetgenOutput run_tetgen(const TetgenInput& input, const std::function<void()>& meanwhile)
{
    // TetGen runs in a child process: an assert inside it (Debian's build keeps them) then ends the child,
    // not the program, and its printf output is captured there instead of reaching our stdout.
    IsolatedResult result = run_isolated(
        "TetGen",
        [&input] {
            tetgenio in;
            tetgenio out;
            fill_input(input, in);
            std::string switches = input.switches;
            try {
                tetrahedralize(switches.data(), &in, &out);
            } catch (int code) {
                throw AlgorithmError(explain_code(code));
            } catch (const std::bad_alloc&) {
                throw AlgorithmError(
                    "TetGen ran out of memory; ask for larger tets (--max-volume) or coarser surfaces");
            }
            return OutputBytes::pack(out);
        },
        meanwhile);
    return OutputBytes::unpack(std::move(result.bytes));
}

} // namespace tissuemesh::volume::detail
