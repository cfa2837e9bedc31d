// Checks an exception's type AND its one-line message.
#pragma once

#include <string>

#include <gtest/gtest.h>

namespace tissuemesh::testing {

/// Runs `call`, expects it to throw `E` whose message contains every one of `parts` and is one line.
template <typename E, typename Call>
void expect_error(Call&& call, std::initializer_list<std::string> parts)
{
    try {
        call();
        ADD_FAILURE() << "no exception; expected one mentioning '" << *parts.begin() << "'";
    } catch (const E& e) {
        const std::string message = e.what();
        for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << "message spans several lines: " << message;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "wrong exception type: " << e.what();
    }
}

} // namespace tissuemesh::testing
