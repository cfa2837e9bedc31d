#include "io/detail/msh4_format.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <map>

#include "core/error.h"
#include "io/detail/msh_common.h"

namespace tissuemesh::io::detail {
namespace {

static_assert(std::endian::native == std::endian::little, "binary .msh code assumes a little-endian host");

/// Values as text (space-separated lines) or as 4.1 binary (size_t as uint64, int as int32, double).
class Writer {
public:
    explicit Writer(bool binary) : binary_(binary) {}
    void size(std::size_t v) { binary_ ? append_binary<std::uint64_t>(out, v) : text(concat(v)); }
    void integer(int v) { binary_ ? append_binary<std::int32_t>(out, v) : text(concat(v)); }
    void real(double v)
    {
        if (binary_) return append_binary<double>(out, v);
        append_real(out, v);
        out += ' ';
    }
    void end_line()
    {
        if (!binary_ && !out.empty() && out.back() == ' ') out.back() = '\n';
    }
    std::string out;

private:
    void text(const std::string& s) { out += s, out += ' '; }
    bool binary_;
};

/// The matching reader; `min_*` are the fewest bytes one value takes (binary sizes, or a digit and a space).
class Reader {
public:
    Reader(ByteReader& source, bool binary) : in(source), binary_(binary) {}
    std::size_t size(const char* what, std::size_t min_bytes_each)
    {
        return binary_ ? in.binary_count<std::uint64_t>(what, min_bytes_each) : in.count(what, min_bytes_each);
    }
    long long tag(const char* what)
    {
        return binary_ ? static_cast<long long>(in.binary<std::uint64_t>(what)) : in.integer(what);
    }
    int integer(const char* what)
    {
        return binary_ ? in.binary<std::int32_t>(what) : static_cast<int>(in.integer(what));
    }
    double real(const char* what) { return binary_ ? in.binary<double>(what) : in.real(what); }
    std::size_t bytes(std::size_t binary_bytes) const { return binary_ ? binary_bytes : 2; }
    ByteReader& in;

private:
    bool binary_;
};

struct Block {
    int dim = 0, tag = 0, type = 0;
    std::vector<std::size_t> elements; ///< face or tet indices into the mesh
};

void append_box(Writer& w, const TetMesh& mesh, const std::vector<std::uint32_t>& corners)
{
    Vec3 low{0, 0, 0}, high{0, 0, 0};
    for (std::size_t i = 0; i < corners.size(); ++i)
        for (int a = 0; a < 3; ++a) {
            const double x = mesh.vertices[corners[i]][static_cast<std::size_t>(a)];
            low[static_cast<std::size_t>(a)] = i == 0 ? x : std::min(low[static_cast<std::size_t>(a)], x);
            high[static_cast<std::size_t>(a)] = i == 0 ? x : std::max(high[static_cast<std::size_t>(a)], x);
        }
    for (const double x : low) w.real(x);
    for (const double x : high) w.real(x);
}

std::vector<Block> blocks_of(const TetMesh& mesh)
{
    std::map<int, Block> faces, tets;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        Block& block = faces[face_tag(mesh.face_sides[f])];
        block = {2, face_tag(mesh.face_sides[f]), 2, std::move(block.elements)};
        block.elements.push_back(f);
    }
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        Block& block = tets[mesh.tet_labels[t]];
        block = {3, mesh.tet_labels[t], 4, std::move(block.elements)};
        block.elements.push_back(t);
    }
    std::vector<Block> blocks;
    for (auto& [tag, block] : faces) blocks.push_back(std::move(block));
    for (auto& [tag, block] : tets) blocks.push_back(std::move(block));
    return blocks;
}

void append_entities(Writer& w, const TetMesh& mesh, const std::vector<Block>& blocks)
{
    const auto surfaces = static_cast<std::size_t>(
        std::count_if(blocks.begin(), blocks.end(), [](const Block& b) { return b.dim == 2; }));
    for (const std::size_t n : {std::size_t{0}, std::size_t{0}, surfaces, blocks.size() - surfaces}) w.size(n);
    w.end_line();
    for (const Block& block : blocks) {
        std::vector<std::uint32_t> corners;
        for (const std::size_t e : block.elements) {
            if (block.dim == 2) corners.insert(corners.end(), mesh.faces[e].begin(), mesh.faces[e].end());
            else corners.insert(corners.end(), mesh.tets[e].begin(), mesh.tets[e].end());
        }
        w.integer(block.tag);
        append_box(w, mesh, corners);
        w.size(1);
        w.integer(block.dim == 2 ? face_physical(mesh.face_sides[block.elements.front()]) : block.tag);
        w.size(0); // bounding entities: a discrete mesh needs none
        w.end_line();
    }
}

void append_nodes(Writer& w, const TetMesh& mesh, const std::vector<Block>& blocks)
{
    const std::size_t n = mesh.vertices.size();
    for (const std::size_t v : {std::size_t{n > 0 ? 1u : 0u}, n, std::size_t{n > 0 ? 1u : 0u}, n}) w.size(v);
    w.end_line();
    if (n == 0) return;
    // Every node in one block on the last entity (a tissue volume when there are tets).
    w.integer(blocks.empty() ? 3 : blocks.back().dim);
    w.integer(blocks.empty() ? 1 : blocks.back().tag);
    w.integer(0);
    w.size(n);
    w.end_line();
    for (std::size_t v = 1; v <= n; ++v) w.size(v), w.end_line();
    for (const Vec3& vertex : mesh.vertices) {
        for (const double c : vertex) w.real(c);
        w.end_line();
    }
}

void append_elements(Writer& w, const TetMesh& mesh, const std::vector<Block>& blocks)
{
    const std::size_t n = mesh.faces.size() + mesh.tets.size();
    for (const std::size_t v : {blocks.size(), n, std::size_t{n > 0 ? 1u : 0u}, n}) w.size(v);
    w.end_line();
    std::size_t id = 1;
    for (const Block& block : blocks) {
        w.integer(block.dim), w.integer(block.tag), w.integer(block.type), w.size(block.elements.size());
        w.end_line();
        for (const std::size_t e : block.elements) {
            w.size(id++);
            if (block.dim == 2)
                for (const std::uint32_t v : mesh.faces[e]) w.size(v + 1);
            else
                for (const std::uint32_t v : mesh.tets[e]) w.size(v + 1);
            w.end_line();
        }
    }
}

/// $Entities: the first physical tag of each surface and volume, by (dim, tag); 0 when it has none.
std::map<std::pair<int, int>, int> parse_entities(Reader& r)
{
    std::array<std::size_t, 4> counts{};
    for (std::size_t& c : counts) c = r.size("entities", r.bytes(4 + 8 + 8));
    std::map<std::pair<int, int>, int> physical;
    for (int dim = 0; dim < 4; ++dim) {
        for (std::size_t e = 0; e < counts[static_cast<std::size_t>(dim)]; ++e) {
            const int tag = r.integer("an entity tag");
            for (int c = 0; c < (dim == 0 ? 3 : 6); ++c) r.real("an entity bound");
            const std::size_t physicals = r.size("physical tags", r.bytes(4));
            int first = 0;
            for (std::size_t p = 0; p < physicals; ++p) {
                const int value = r.integer("a physical tag");
                if (p == 0) first = value;
            }
            if (dim > 0) {
                const std::size_t bounding = r.size("bounding entities", r.bytes(4));
                for (std::size_t b = 0; b < bounding; ++b) r.integer("a bounding entity");
            }
            physical[{dim, tag}] = first;
        }
    }
    return physical;
}

void parse_nodes(Reader& r, TetMesh& mesh, NodeIndex& index)
{
    const std::size_t blocks = r.size("node blocks", r.bytes(20));
    const std::size_t count = r.size("nodes", r.bytes(32));
    r.size("the smallest node tag", 0), r.size("the largest node tag", 0);
    mesh.vertices.resize(count);
    index.reserve(count);
    std::size_t done = 0;
    for (std::size_t b = 0; b < blocks; ++b) {
        const int dim = r.integer("an entity dimension");
        r.integer("an entity tag");
        const int parametric = r.integer("the parametric flag");
        const std::size_t n = r.size("nodes in a block", r.bytes(32));
        if (n > count - done)
            r.in.fail(concat(n, " nodes in a block exceed the ", count, " announced"), "the file is corrupt");
        for (std::size_t i = 0; i < n; ++i) index.add(r.tag("a node tag"));
        const int extra = parametric != 0 ? std::clamp(dim, 0, 3) : 0;
        for (std::size_t i = 0; i < n; ++i) {
            for (double& c : mesh.vertices[done + i]) c = r.real("a coordinate");
            for (int p = 0; p < extra; ++p) r.real("a parametric coordinate");
        }
        done += n;
    }
    if (done != count)
        r.in.fail(concat("the node blocks hold ", done, " of the ", count, " nodes announced"), "the file is corrupt");
    index.finish(r.in);
}

void parse_elements(Reader& r, TetMesh& mesh, const NodeIndex& nodes,
                    const std::map<std::pair<int, int>, int>& physical)
{
    const std::size_t blocks = r.size("element blocks", r.bytes(20));
    const std::size_t count = r.size("elements", r.bytes(16));
    r.size("the smallest element tag", 0), r.size("the largest element tag", 0);
    std::size_t done = 0;
    for (std::size_t b = 0; b < blocks; ++b) {
        const int dim = r.integer("an entity dimension");
        const int tag = r.integer("an entity tag");
        const int type = r.integer("an element type");
        const int corners = gmsh_element_nodes(type);
        if (corners < 0) r.in.fail(concat("element type ", type, " is not supported"), "save tets and triangles only");
        const std::size_t n = r.size("elements in a block", r.bytes(8 * (1 + static_cast<std::size_t>(corners))));
        if (n > count - done)
            r.in.fail(concat(n, " elements in a block exceed the ", count, " announced"), "the file is corrupt");
        const auto found = physical.find({dim, tag});
        const int group = found != physical.end() && found->second != 0 ? found->second : tag;
        if (type == 4 && (group < 0 || group > 65535))
            r.in.fail(concat("volume ", tag, " has physical tag ", group, ", which is not a label"),
                      "tag tissues 0..65535");
        for (std::size_t e = 0; e < n; ++e) {
            r.tag("an element tag");
            std::array<std::uint32_t, 4> v{};
            for (int c = 0; c < corners; ++c) {
                const std::uint32_t vertex = nodes.at(r.tag("a node tag"), r.in);
                if (c < 4) v[static_cast<std::size_t>(c)] = vertex;
            }
            if (type == 4) add_tet(mesh, v, static_cast<Label>(group));
            if (type == 2) mesh.faces.push_back({v[0], v[1], v[2]}), mesh.face_sides.push_back(face_pair(group, tag));
        }
        done += n;
    }
}

} // namespace

std::string format_msh4(const TetMesh& mesh, bool binary)
{
    const std::vector<Block> blocks = blocks_of(mesh);
    Writer w(binary);
    w.out = binary ? "$MeshFormat\n4.1 1 8\n" : "$MeshFormat\n4.1 0 8\n";
    if (binary) append_binary<std::int32_t>(w.out, 1), w.out += '\n';
    w.out += "$EndMeshFormat\n" + format_physical_names(mesh) + "$Entities\n";
    append_entities(w, mesh, blocks);
    w.out += binary ? "\n$EndEntities\n$Nodes\n" : "$EndEntities\n$Nodes\n";
    append_nodes(w, mesh, blocks);
    w.out += binary ? "\n$EndNodes\n$Elements\n" : "$EndNodes\n$Elements\n";
    append_elements(w, mesh, blocks);
    w.out += binary ? "\n$EndElements\n" : "$EndElements\n";
    return std::move(w.out);
}

TetMesh parse_msh4(ByteReader& in)
{
    const bool binary = parse_mesh_format(in, "save with 8-byte size_t");
    TetMesh mesh;
    NodeIndex nodes;
    std::map<std::pair<int, int>, int> physical;
    bool have_nodes = false;
    Reader r(in, binary);
    for (std::string_view section = in.word(); !section.empty(); section = in.word()) {
        const std::string name(section);
        if (binary && (name == "$Entities" || name == "$Nodes" || name == "$Elements")) in.skip_line();
        if (name == "$PhysicalNames") {
            parse_physical_names(in, mesh.names);
        } else if (name == "$Entities") {
            physical = parse_entities(r);
        } else if (name == "$Nodes") {
            parse_nodes(r, mesh, nodes);
            have_nodes = true;
        } else if (name == "$Elements") {
            if (!have_nodes) in.fail("$Elements comes before $Nodes", "the file is corrupt; write it again");
            parse_elements(r, mesh, nodes, physical);
        } else if (name.size() > 1 && name[0] == '$') {
            in.skip_past(concat("$End", name.substr(1))); // $PartitionedEntities, $NodeData, ...: not ours
            continue;
        } else {
            in.fail(concat("unexpected \"", name.substr(0, 40), "\" between sections"),
                    "the file is corrupt; write it again");
        }
        in.expect(concat("$End", name.substr(1)));
    }
    return mesh;
}

} // namespace tissuemesh::io::detail
