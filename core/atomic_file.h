// Outputs are valid or absent: every file is written under a temporary name and renamed when complete.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>

namespace tissuemesh {

/// Writes `path` atomically. `write` receives a temporary path in the same directory that keeps the
/// full file name as its suffix (so "head.nii.gz" stays recognisable by extension); when `write`
/// returns, the temporary file is renamed onto `path`; when it throws, the temporary is removed and
/// the exception propagates, so `path` is never left half-written.
/// @throws IoError when the directory does not exist or the rename fails.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path& temporary)>& write);

/// Writes `path` atomically through a binary stream: `write` fills it; the file is kept only when the
/// stream opened, `write` returned and the bytes reached the disk.
/// @throws IoError naming `path` when it cannot be opened or written (permissions, a full disk).
void write_stream_atomically(const std::filesystem::path& path, const std::function<void(std::ostream& out)>& write);

/// Writes `text` to `path` atomically.
void write_text_atomically(const std::filesystem::path& path, const std::string& text);

/// Throws IoError naming `path` when it does not exist, is a directory, or cannot be opened for reading.
void require_readable_file(const std::filesystem::path& path);

/// The whole content of `path` as bytes.
/// @throws IoError (naming `path`) when it is missing, a directory, unreadable, or the read fails
std::string read_file_bytes(const std::filesystem::path& path);

/// The file name's extension(s) in lower case, with compression kept: "a/b.NII.gz" -> ".nii.gz".
std::string full_extension(const std::filesystem::path& path);

} // namespace tissuemesh
