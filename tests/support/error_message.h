// The message of a library call's InputError, for tests that check it word for word.
#pragma once

#include <string>

#include "core/error.h"

namespace tissuemesh::testing {

/// The message of the InputError that `call` throws ("" when it throws none).
template <class Call>
std::string input_error_message(Call&& call)
{
    try {
        call();
    } catch (const InputError& error) {
        return error.what();
    }
    return "";
}

} // namespace tissuemesh::testing
