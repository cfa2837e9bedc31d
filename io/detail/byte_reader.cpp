#include "io/detail/byte_reader.h"

#include <cctype>
#include <charconv>
#include <fstream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"

namespace tissuemesh::io::detail {

namespace {
bool is_space(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }
} // namespace

std::string_view ByteReader::word()
{
    while (at_ < bytes_.size() && is_space(bytes_[at_])) ++at_;
    const std::size_t start = at_;
    while (at_ < bytes_.size() && !is_space(bytes_[at_])) ++at_;
    return std::string_view(bytes_).substr(start, at_ - start);
}

std::string_view ByteReader::next_word(const char* expected)
{
    const std::string_view w = word();
    if (w.empty()) truncated(expected);
    return w;
}

void ByteReader::expect(std::string_view keyword)
{
    const std::string_view w = word();
    if (w != keyword)
        fail(concat("expected ", keyword, " but found \"", w.substr(0, 40), "\""),
             "the file is truncated or malformed; write it again");
}

long long ByteReader::integer(const char* expected)
{
    const std::string_view w = next_word(expected);
    long long value = 0;
    const auto [end, error] = std::from_chars(w.data(), w.data() + w.size(), value);
    if (error != std::errc() || end != w.data() + w.size())
        fail(concat("expected ", expected, " but found \"", w.substr(0, 40), "\""),
             "the file is corrupt; write it again");
    return value;
}

double ByteReader::real(const char* expected)
{
    const std::string_view w = next_word(expected);
    double value = 0;
    const auto [end, error] = std::from_chars(w.data(), w.data() + w.size(), value);
    if (error != std::errc() || end != w.data() + w.size())
        fail(concat("expected ", expected, " but found \"", w.substr(0, 40), "\""),
             "the file is corrupt; write it again");
    return value;
}

std::size_t ByteReader::count(const char* items, std::size_t min_bytes_each)
{
    const long long value = integer(items);
    return checked_count(value, value < 0, items, min_bytes_each);
}

std::size_t ByteReader::checked_count(long long value, bool negative, const char* items,
                                      std::size_t min_bytes_each) const
{
    if (negative) fail(concat(value, " ", items, " is not a count"), "the file is corrupt; write it again");
    const auto count = static_cast<unsigned long long>(value);
    if (min_bytes_each > 0 && count > remaining() / min_bytes_each)
        fail(concat("expected ", count, " ", items, " but only ", remaining(), " bytes follow"),
             "the file is truncated or corrupt; write it again");
    return static_cast<std::size_t>(count);
}

std::string_view ByteReader::rest_of_line()
{
    const std::size_t start = at_;
    while (at_ < bytes_.size() && bytes_[at_] != '\n') ++at_;
    std::string_view line = std::string_view(bytes_).substr(start, at_ - start);
    if (at_ < bytes_.size()) ++at_;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return line;
}

void ByteReader::skip_line() { rest_of_line(); }

void ByteReader::skip_past(std::string_view marker)
{
    const std::size_t found = bytes_.find(marker, at_);
    if (found == std::string::npos) fail(concat("no ", marker), "the file is truncated; write it again");
    at_ = found + marker.size();
}

void ByteReader::fail(const std::string& problem, const std::string& fix) const
{
    throw IoError(concat(what_, ": ", problem, " (at byte ", at_, "); ", fix));
}

void ByteReader::truncated(const char* expected) const
{
    fail(concat("the data ends where ", expected, " should be"), "the file is truncated; write it again");
}

} // namespace tissuemesh::io::detail
