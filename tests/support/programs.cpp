#include "tests/support/programs.h"

#include <fcntl.h>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

#include "tests/support/complexes.h"
#include "volume/tetrahedralize.h"

namespace tissuemesh::testing {
namespace fs = std::filesystem;

CliResult run_program(const std::string& program, const std::vector<std::string>& args, const fs::path& working_dir)
{
    TempDir capture;
    const fs::path out_path = capture / "stdout", err_path = capture / "stderr";
    const pid_t pid = ::fork();
    if (pid == 0) {
        const int out = ::open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int in = ::open("/dev/null", O_RDONLY);
        ::dup2(out, 1), ::dup2(err, 2), ::dup2(in, 0);
        if (!working_dir.empty() && ::chdir(working_dir.c_str()) != 0) ::_exit(126);
        std::vector<char*> argv{const_cast<char*>(program.c_str())};
        for (const std::string& arg : args) argv.push_back(const_cast<char*>(arg.c_str()));
        argv.push_back(nullptr);
        ::execvp(program.c_str(), argv.data());
        ::_exit(127);
    }
    CliResult result;
    int status = 0;
    if (pid > 0 && ::waitpid(pid, &status, 0) == pid)
        result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    auto slurp = [](const fs::path& path) {
        std::ifstream in(path, std::ios::binary);
        std::ostringstream text;
        text << in.rdbuf();
        return text.str();
    };
    result.out = slurp(out_path);
    result.err = slurp(err_path);
    return result;
}

TetMesh nested_cubes_mesh()
{
    VoxelBlock block;
    block.nx = block.ny = block.nz = 4;
    block.labels.assign(64, 1);
    for (std::size_t k = 1; k < 3; ++k)
        for (std::size_t j = 1; j < 3; ++j)
            for (std::size_t i = 1; i < 3; ++i) block.labels[i + 4 * (j + 4 * k)] = 2;
    InterfaceComplex complex = voxel_faces(block);
    complex.names = {{1, "outer"}, {2, "inner"}};
    volume::TetrahedralizeOptions options;
    options.max_volume_mm3 = 0.5;  // a few hundred tets: several per tissue, fast everywhere
    return volume::tetrahedralize(complex, options);
}

std::map<Label, double> tissue_volumes(const TetMesh& mesh)
{
    std::map<Label, double> volumes;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) volumes[mesh.tet_labels[t]] += signed_volume(mesh, t);
    return volumes;
}

} // namespace tissuemesh::testing
