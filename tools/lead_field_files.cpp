#include "tools/lead_field_files.h"

#include <cstdint>
#include <cstdio>
#include <cstring>

#include "core/atomic_file.h"
#include "core/error.h"

namespace tissuemesh::tools {
namespace {

// A sidecar lists every sensor and source: 64 MiB holds far more than max_sources of them.
constexpr std::uintmax_t max_sidecar_bytes = 64u << 20;

class Fnv1a {
public:
    template <typename T>
    void add(const std::vector<T>& values)
    {
        const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
        for (std::size_t k = 0; k < values.size() * sizeof(T); ++k) hash_ = (hash_ ^ bytes[k]) * 0x100000001b3ull;
    }
    std::string hex() const
    {
        char text[17];
        std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash_));
        return text;
    }

private:
    std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

nlohmann::json read_sidecar(const std::filesystem::path& path)
{
    require_readable_file(path);
    std::error_code error;
    if (std::filesystem::file_size(path, error) > max_sidecar_bytes || error)
        throw IoError(
            concat(path.string(), ": larger than ", max_sidecar_bytes >> 20, " MiB; not a lead-field sidecar"));
    try {
        return nlohmann::json::parse(read_file_bytes(path));
    } catch (const nlohmann::json::exception& failure) {
        throw IoError(
            concat(path.string(), ": not valid JSON (", failure.what(), "); write it again with tm-leadfield"));
    }
}

} // namespace

std::filesystem::path sidecar_path(const std::filesystem::path& npy)
{
    std::filesystem::path sidecar = npy;
    if (sidecar.extension() == ".npy") return sidecar.replace_extension(".json");
    return sidecar += ".json";
}

std::string mesh_fingerprint(const TetMesh& mesh)
{
    Fnv1a hash;
    hash.add(mesh.vertices);
    hash.add(mesh.tets);
    hash.add(mesh.tet_labels);
    return hash.hex();
}

nlohmann::json mesh_description(const std::string& path, const TetMesh& mesh)
{
    return {{"path", path},
            {"nodes", mesh.vertex_count()},
            {"tets", mesh.tet_count()},
            {"fingerprint", mesh_fingerprint(mesh)}};
}

nlohmann::json conductivity_description(const TetMesh& mesh, const fem::Conductivities& conductivities)
{
    nlohmann::json table = nlohmann::json::object();
    for (const auto& [label, sigma] : conductivities.by_label) {
        const auto name = mesh.names.find(label);
        const std::string key = name == mesh.names.end() ? std::to_string(label) : name->second;
        if (sigma == fem::isotropic(sigma[0])) table[key] = sigma[0];
        else table[key] = std::vector<double>(sigma.begin(), sigma.end());
    }
    return table;
}

void write_lead_field(const std::filesystem::path& npy, std::size_t rows, std::size_t columns, const double* values,
                      const nlohmann::json& sidecar)
{
    io::write_npy(npy, rows, columns, values);
    try {
        write_text_atomically(sidecar_path(npy), sidecar.dump(1) + "\n");
    } catch (...) {
        std::error_code ignored;
        std::filesystem::remove(npy, ignored);
        throw;
    }
}

TdcsLeadFieldFile read_tdcs_lead_field(const std::filesystem::path& npy, const TetMesh& mesh)
{
    const std::filesystem::path json_path = sidecar_path(npy);
    const nlohmann::json sidecar = read_sidecar(json_path);
    const std::string file = json_path.string();
    TdcsLeadFieldFile read;
    try {
        if (sidecar.at("kind").get<std::string>() != "tdcs")
            throw IoError(concat(file, ": a lead field of kind '", sidecar.at("kind").get<std::string>(),
                                 "', not tdcs; ", "give the --tdcs-output of tm-leadfield"));
        const nlohmann::json& described = sidecar.at("mesh");
        if (described.at("nodes").get<std::size_t>() != mesh.vertex_count() ||
            described.at("fingerprint").get<std::string>() != mesh_fingerprint(mesh))
            throw InputError(concat(file, ": computed for the mesh ", described.at("path").get<std::string>(), " (",
                                    described.at("nodes").get<std::size_t>(), " nodes), not this one (",
                                    mesh.vertex_count(), " nodes, or the same count but other nodes or tets); run ",
                                    "tm-leadfield on this mesh"));
        for (const nlohmann::json& electrode : sidecar.at("electrodes")) {
            read.names.push_back(electrode.at("name").get<std::string>());
            const std::vector<double> centre = electrode.at("centre_mm").get<std::vector<double>>();
            if (centre.size() != 3) throw IoError(concat(file, ": an electrode centre without 3 coordinates"));
            read.centres_mm.push_back({centre[0], centre[1], centre[2]});
            read.radii_mm.push_back(electrode.at("radius_mm").get<double>());
        }
        read.lead_field.reference = sidecar.at("reference_index").get<std::size_t>();
    } catch (const nlohmann::json::exception& failure) {
        throw IoError(
            concat(file, ": not a tDCS lead-field sidecar (", failure.what(), "); write it again with tm-leadfield"));
    }
    const std::size_t count = read.names.size();
    if (count < 2 || read.lead_field.reference >= count)
        throw IoError(concat(file, ": ", count, " electrodes and reference ", read.lead_field.reference + 1,
                             "; write it again with tm-leadfield"));
    const io::NpyMatrix matrix = io::read_npy(npy);
    if (matrix.rows != count - 1 || matrix.columns != mesh.vertex_count())
        throw IoError(concat(npy.string(), ": ", matrix.rows, " x ", matrix.columns, " values where its sidecar says ",
                             count - 1, " electrodes x ", mesh.vertex_count(),
                             " nodes; write both again with tm-leadfield"));
    for (std::size_t e = 0; e < count; ++e)
        if (e != read.lead_field.reference) read.lead_field.electrodes.push_back(e);
    read.lead_field.potentials_v_per_a.resize(static_cast<Eigen::Index>(matrix.rows),
                                              static_cast<Eigen::Index>(matrix.columns));
    std::memcpy(read.lead_field.potentials_v_per_a.data(), matrix.values.data(), matrix.values.size() * sizeof(double));
    return read;
}

} // namespace tissuemesh::tools
