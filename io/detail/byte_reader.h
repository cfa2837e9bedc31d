// A bounds-checked cursor over a whole file's bytes, for text and binary mesh formats alike: every read
// names the file and the byte offset when the data ends early or is malformed.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>

namespace tissuemesh::io::detail {

class ByteReader {
public:
    /// `bytes` must outlive the reader; `what` names the file in messages.
    ByteReader(const std::string& bytes, std::string what) : bytes_(bytes), what_(std::move(what)) {}

    const std::string& what() const { return what_; }
    std::size_t position() const { return at_; }
    std::size_t remaining() const { return bytes_.size() - at_; }

    /// The next whitespace-separated word, or "" at the end of the data.
    std::string_view word();
    /// The next word; throws (naming `expected`) at the end of the data.
    std::string_view next_word(const char* expected);
    /// Throws unless the next word is `keyword`.
    void expect(std::string_view keyword);
    /// The next word as an integer / a finite-or-not double; throws naming `expected` when it is not one.
    long long integer(const char* expected);
    double real(const char* expected);
    /// A non-negative text count of items that take at least `min_bytes_each` bytes of the rest of the file.
    std::size_t count(const char* items, std::size_t min_bytes_each);
    /// Everything up to the end of the line (without the newline); moves past it.
    std::string_view rest_of_line();
    /// Moves just past the next newline (binary data follows the line of its count).
    void skip_line();
    /// Moves past the next occurrence of `marker`; throws when there is none.
    void skip_past(std::string_view marker);

    /// A raw little-endian value.
    template <typename T>
    T binary(const char* expected)
    {
        if (remaining() < sizeof(T)) truncated(expected);
        T value;
        std::memcpy(&value, bytes_.data() + at_, sizeof(T));
        at_ += sizeof(T);
        return value;
    }
    /// A binary count (read as T) of items of at least `min_bytes_each` bytes each.
    template <typename T>
    std::size_t binary_count(const char* items, std::size_t min_bytes_each)
    {
        const auto value = binary<T>(items);
        return checked_count(static_cast<long long>(value), value < 0, items, min_bytes_each);
    }

    /// Throws IoError "file: problem (at byte N); fix".
    [[noreturn]] void fail(const std::string& problem, const std::string& fix) const;
    [[noreturn]] void truncated(const char* expected) const;

private:
    std::size_t checked_count(long long value, bool negative, const char* items, std::size_t min_bytes_each) const;

    const std::string& bytes_;
    std::string what_;
    std::size_t at_ = 0;
};

} // namespace tissuemesh::io::detail
