// Checks that a label image is refused: the reader's exception type AND its one-line message.
#pragma once

#include <filesystem>
#include <string>

#include "io/read_label_image.h"
#include "tests/io/expect_error.h"

namespace tissuemesh::testing {

/// Reads `file` as a label image and expects `E` whose message contains every one of `parts` and is one line.
template <typename E>
void expect_read_error(const std::filesystem::path& file, std::initializer_list<std::string> parts)
{
    expect_error<E>([&] { io::read_label_image(file); }, parts);
}

} // namespace tissuemesh::testing
