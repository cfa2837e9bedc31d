// A fixture for the tests of the small readers (tables, lead-field files): input files written from text into a
// temporary folder, and the check that a reader refuses one with our typed error.
#pragma once

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>

#include <gtest/gtest.h>

#include "tests/io/expect_error.h"
#include "tests/support/cli.h"

namespace tissuemesh::testing {

class ReaderFiles : public ::testing::Test {
protected:
    /// Writes `text` byte for byte as `name` in the test's folder; returns its path.
    std::string write(const std::string& name, const std::string& text)
    {
        std::ofstream(dir_ / name, std::ios::binary) << text;
        return (dir_ / name).string();
    }

    /// Writes `text` as `name` and expects `read` to refuse it with an `E` whose message holds every part.
    template <typename E, typename Read>
    void expect_refused(Read read, const std::string& name, const std::string& text,
                        std::initializer_list<std::string> parts)
    {
        SCOPED_TRACE(name);
        const std::string file = write(name, text);
        expect_error<E>([&] { (void)read(file); }, parts);
    }

    TempDir dir_;
};

} // namespace tissuemesh::testing
