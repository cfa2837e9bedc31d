// A libFuzzer target for one file reader: the fuzzer's bytes become a file with the reader's extension
// (TM_FUZZ_EXTENSION) and go through it. Our typed errors (tissuemesh::Error) are the expected answer to bad
// bytes. Anything else is a finding: a crash or sanitizer report, another exception escaping, a hang
// (-timeout), or an allocation over -malloc_limit_mb (a reader must not allocate what the file cannot hold).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "io/read_conductivity_table.h"
#include "io/npy.h"
#include "io/read_electrodes.h"
#include "io/read_label_image.h"
#include "io/read_meg_sensors.h"
#include "io/read_sensors.h"
#include "io/read_sources.h"
#include "io/surface_io.h"
#include "io/tet_mesh_io.h"

namespace {

namespace fs = std::filesystem;

/// A private folder for this process (in memory when /dev/shm exists): the input file, and for the raw +
/// JSON reader a fixed 4x4x4 voxel file the fuzzed sidecar may point to.
const fs::path& work_dir()
{
    static const fs::path dir = [] {
        const fs::path base = fs::exists("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
        fs::path made = base / ("tissuemesh-fuzz-" + std::to_string(::getpid()));
        fs::create_directories(made);
        std::ofstream(made / "voxels.raw", std::ios::binary) << std::string(64, '\1');
        return made;
    }();
    return dir;
}

void read_as_format(const fs::path& file)
{
#if defined(TM_FUZZ_IMAGE)
    (void)tissuemesh::io::read_label_image(file);
#elif defined(TM_FUZZ_SURFACE)
    (void)tissuemesh::io::read_surface(file);
#elif defined(TM_FUZZ_MESH)
    (void)tissuemesh::io::read_tet_mesh(file);
#elif defined(TM_FUZZ_NAMES)
    (void)tissuemesh::io::read_tissue_names(file);
#elif defined(TM_FUZZ_CONDUCTIVITY)
    (void)tissuemesh::io::read_conductivity_table(file);
#elif defined(TM_FUZZ_ELECTRODES)
    (void)tissuemesh::io::read_electrodes(file);
#elif defined(TM_FUZZ_SENSORS)
    (void)tissuemesh::io::read_sensors(file);
#elif defined(TM_FUZZ_SOURCES)
    (void)tissuemesh::io::read_sources(file);
#elif defined(TM_FUZZ_MEG_SENSORS)
    (void)tissuemesh::io::read_meg_sensors(file);
#elif defined(TM_FUZZ_NPY)
    (void)tissuemesh::io::read_npy(file);
#else
#error                                                                                                                 \
    "define one of TM_FUZZ_IMAGE, TM_FUZZ_SURFACE, TM_FUZZ_MESH, TM_FUZZ_NAMES, TM_FUZZ_CONDUCTIVITY, TM_FUZZ_ELECTRODES, TM_FUZZ_SENSORS, TM_FUZZ_SOURCES, TM_FUZZ_MEG_SENSORS, TM_FUZZ_NPY"
#endif
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const fs::path file = work_dir() / ("input" TM_FUZZ_EXTENSION);
    {
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    try {
        read_as_format(file);
    } catch (const tissuemesh::Error&) {
        // The reader said what is wrong: the intended outcome for bad bytes.
    }
    return 0;
}
