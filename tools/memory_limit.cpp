#include "tools/memory_limit.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>

#include "core/error.h"

namespace tissuemesh::tools {
namespace {

/// The first number in the file at `path` ("max" and missing files: none).
std::optional<std::uint64_t> read_number(const char* path)
{
    std::ifstream in(path);
    std::uint64_t value = 0;
    if (!(in >> value)) return std::nullopt;
    return value;
}

/// The value of `key` ("MemAvailable:", "inactive_file") in a "key value" file, times `unit`.
std::optional<std::uint64_t> read_field(const char* path, const std::string& key, std::uint64_t unit)
{
    std::ifstream in(path);
    std::string name;
    std::uint64_t value = 0;
    while (in >> name >> value) {
        if (name == key) return value * unit;
        in.ignore(1 << 20, '\n');
    }
    return std::nullopt;
}

/// What the cgroup leaves: limit - usage + reclaimable file cache; none when unlimited or unreadable.
std::optional<std::uint64_t> cgroup_available(const char* limit_path, const char* usage_path, const char* stat_path)
{
    const auto limit = read_number(limit_path);
    const auto usage = read_number(usage_path);
    if (!limit || !usage || *limit >= (std::uint64_t{1} << 60)) return std::nullopt; // v1 writes 2^63 - 4096 for none
    const std::uint64_t cache = read_field(stat_path, "inactive_file", 1).value_or(0);
    const std::uint64_t used = *usage > cache ? *usage - cache : 0;
    return *limit > used ? *limit - used : 0;
}

} // namespace

std::uint64_t available_memory_bytes()
{
    std::optional<std::uint64_t> available = read_field("/proc/meminfo", "MemAvailable:", 1024);
    for (const auto& group :
         {cgroup_available("/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory.current", "/sys/fs/cgroup/memory.stat"),
          cgroup_available("/sys/fs/cgroup/memory/memory.limit_in_bytes", "/sys/fs/cgroup/memory/memory.usage_in_bytes",
                           "/sys/fs/cgroup/memory/memory.stat")})
        if (group) available = available ? std::min(*available, *group) : *group;
    return available.value_or(0);
}

std::uint64_t resident_memory_bytes()
{
    std::ifstream statm("/proc/self/statm");
    std::uint64_t size = 0, resident = 0;
    if (!(statm >> size >> resident)) return 0;
    return resident * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
}

std::string format_bytes(double bytes)
{
    const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB"};
    int unit = 0;
    while (bytes >= 1024 && unit < 5) bytes /= 1024, ++unit;
    char text[32];
    std::snprintf(text, sizeof text, unit == 0 || bytes >= 100 ? "%.0f %s" : "%.1f %s", bytes, units[unit]);
    return text;
}

std::string format_count(double count)
{
    char text[32];
    if (count >= 1e9) std::snprintf(text, sizeof text, "%.1f G", count / 1e9);
    else if (count >= 1e6) std::snprintf(text, sizeof text, "%.1f M", count / 1e6);
    else if (count >= 1e4) std::snprintf(text, sizeof text, "%.0f k", count / 1e3);
    else std::snprintf(text, sizeof text, "%.0f", count);
    return text;
}

void require_memory(const MemoryLimit& limit, const std::string& subject, double data_bytes, const std::string& detail,
                    const std::string& fix)
{
    if (limit.bytes == 0) return;
    const double held = static_cast<double>(limit.program_bytes);
    const double needed = held + data_bytes;
    if (needed <= static_cast<double>(limit.bytes)) return;
    const std::string over = limit.from_flag
                                 ? concat("more than --max-memory ", format_bytes(static_cast<double>(limit.bytes)),
                                          "; ", fix, " or raise --max-memory")
                                 : concat("more than the ", format_bytes(static_cast<double>(limit.bytes)),
                                          " this machine has available; ", fix,
                                          ", free memory, or set --max-memory (MiB) "
                                          "to try anyway");
    throw InputError(concat(subject, ": needs about ", format_bytes(needed), " (", detail, ", and ", format_bytes(held),
                            " for the program), ", over));
}

ImageSizeCheck image_memory_check(const MemoryLimit& limit, const std::string& path, double step_bytes_per_voxel,
                                  const std::string& fix)
{
    return [limit, path, step_bytes_per_voxel, fix](const Dims& dims, const Vec3&, std::size_t file_bytes_per_voxel) {
        const double voxels =
            static_cast<double>(dims[0]) * static_cast<double>(dims[1]) * static_cast<double>(dims[2]);
        const double per_voxel = static_cast<double>(file_bytes_per_voxel) + step_bytes_per_voxel;
        require_memory(limit, path, voxels * per_voxel,
                       concat(format_count(voxels), " voxels x ", format_bytes(per_voxel)), fix);
    };
}

} // namespace tissuemesh::tools
