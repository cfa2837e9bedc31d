#include "volume/detail/tetgen_adapter.h"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include <tetgen.h>

#include "core/error.h"

namespace tissuemesh::volume::detail {
namespace {

/// Redirects the process's standard output to a temporary file while alive: TetGen prints with printf,
/// and a library must not print. The captured text serves the error message.
class StdoutCapture {
public:
    StdoutCapture()
    {
        std::fflush(stdout);
        file_ = std::tmpfile();
        saved_ = ::dup(STDOUT_FILENO);
        if (file_ != nullptr && saved_ >= 0) ::dup2(::fileno(file_), STDOUT_FILENO);
    }
    ~StdoutCapture() { restore(); }
    StdoutCapture(const StdoutCapture&) = delete;
    StdoutCapture& operator=(const StdoutCapture&) = delete;

    /// Restores standard output and returns what was printed meanwhile.
    std::string restore()
    {
        if (saved_ < 0) return text_;
        std::fflush(stdout);
        ::dup2(saved_, STDOUT_FILENO);
        ::close(saved_);
        saved_ = -1;
        if (file_ != nullptr) {
            std::rewind(file_);
            char buffer[4096];
            std::size_t n;
            while ((n = std::fread(buffer, 1, sizeof buffer, file_)) > 0) text_.append(buffer, n);
            std::fclose(file_);
            file_ = nullptr;
        }
        return text_;
    }

private:
    std::FILE* file_ = nullptr;
    int saved_ = -1;
    std::string text_;
};

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

/// The last non-empty lines TetGen printed, joined on one line.
std::string last_lines(const std::string& text, int count)
{
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (line.find_first_not_of(" \t") != std::string::npos) lines.push_back(line.substr(line.find_first_not_of(" \t")));
    std::string joined;
    for (std::size_t i = lines.size() > static_cast<std::size_t>(count) ? lines.size() - count : 0; i < lines.size(); ++i)
        joined += (joined.empty() ? "" : " / ") + lines[i];
    return joined;
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

TetgenOutput read_output(const tetgenio& out)
{
    TetgenOutput result;
    result.points.assign(out.pointlist, out.pointlist + 3 * out.numberofpoints);
    result.tets.resize(out.numberoftetrahedra);
    for (int t = 0; t < out.numberoftetrahedra; ++t)
        for (int c = 0; c < 4; ++c) result.tets[t][c] = out.tetrahedronlist[t * out.numberofcorners + c];
    if (out.numberoftetrahedronattributes > 0)
        for (int t = 0; t < out.numberoftetrahedra; ++t)
            result.tet_attributes.push_back(out.tetrahedronattributelist[t * out.numberoftetrahedronattributes]);
    result.faces.resize(out.numberoftrifaces);
    result.face_markers.resize(out.numberoftrifaces, 0);
    for (int f = 0; f < out.numberoftrifaces; ++f) {
        for (int c = 0; c < 3; ++c) result.faces[f][c] = out.trifacelist[3 * f + c];
        if (out.trifacemarkerlist != nullptr) result.face_markers[f] = out.trifacemarkerlist[f];
    }
    return result;
}

} // namespace

TetgenOutput run_tetgen(const TetgenInput& input)
{
    tetgenio in;
    tetgenio out;
    fill_input(input, in);
    std::string switches = input.switches;
    StdoutCapture capture;
    try {
        tetrahedralize(switches.data(), &in, &out);
    } catch (int code) {
        const std::string printed = capture.restore();
        throw AlgorithmError(concat(explain_code(code), " (TetGen said: ", last_lines(printed, 3), ")"));
    } catch (const std::bad_alloc&) {
        capture.restore();
        throw AlgorithmError("TetGen ran out of memory; ask for larger tets (--max-volume) or coarser surfaces");
    }
    capture.restore();
    return read_output(out);
}

} // namespace tissuemesh::volume::detail
