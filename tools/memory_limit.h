// How much memory a tool may use (--max-memory, else what the machine has available), and the check that
// steps make before their big allocations: a refusal with a message beats the kernel's OOM killer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

#include "core/label_image.h"

namespace tissuemesh::tools {

/// The memory a run may use.
struct MemoryLimit {
    std::uint64_t bytes = 0;         ///< 0: no limit known (nothing is refused)
    bool from_flag = false;          ///< set by --max-memory (else: the memory available when the tool started,
                                     ///< plus program_bytes)
    std::uint64_t program_bytes = 0; ///< resident memory of the program itself when the tool started
};

/// The memory this process may still use: /proc/meminfo's MemAvailable, or less when the process's
/// cgroup (v2 memory.max, v1 memory.limit_in_bytes) leaves less: its limit minus its usage plus the
/// reclaimable file cache it holds. 0 when none of them can be read.
std::uint64_t available_memory_bytes();

/// This process's resident memory now (bytes; /proc/self/statm), 0 when unknown.
std::uint64_t resident_memory_bytes();

/// "12.3 GiB", "340 MiB", "12 KiB", "100 B".
std::string format_bytes(double bytes);

/// "7.7 M", "530 k", "125": counts in messages.
std::string format_count(double count);

/// Refuses (InputError, tools exit 2) when the program plus `data_bytes` exceeds the limit:
///     "<subject>: needs about 12.3 GiB (<detail>, and 20 MiB for the program), more than --max-memory 8.0 GiB;
///      <fix> or raise --max-memory"
/// `data_bytes` is the step's whole peak beyond the program itself, what it has read included (the resident
/// memory after a read also counts freed buffers the allocator keeps, so it is no measure of what is held).
/// `subject` names the input (a file), `detail` says where the figure comes from ("7.7 M voxels x 15 B"),
/// `fix` what the user can do ("crop or resample it (tm-prep --spacing-mm 2)").
void require_memory(const MemoryLimit& limit, const std::string& subject, double data_bytes, const std::string& detail,
                    const std::string& fix);

/// The signature of io::ReadImageOptions::before_voxels (kept here so that tools need not link io for it).
using ImageSizeCheck = std::function<void(const Dims& dims, const Vec3& spacing_mm, std::size_t file_bytes_per_voxel)>;

/// A check for io::ReadImageOptions::before_voxels: the image's voxels times (its file's bytes per voxel +
/// `step_bytes_per_voxel`) must fit the limit. `step_bytes_per_voxel` is what the tool's step holds per
/// voxel besides the file's voxels (measured: see the tools).
ImageSizeCheck image_memory_check(const MemoryLimit& limit, const std::string& path, double step_bytes_per_voxel,
                                  const std::string& fix);

} // namespace tissuemesh::tools
