#pragma once
// Errors by kind. The CLI maps them to exit codes:
//   InputError   -> 2  bad input or usage: a scene, a volume file, an argument
//   RuntimeError -> 1  the input was fine but the work failed: device, disk, driver
//     ResourceError    a device limit, the memory budget, the device out of
//                      memory or lost: the next frames would fail the same
//                      way, so a sequence stops there
// Messages name where the problem is (a file, a JSON pointer, an argument) and
// what was expected, so a user can fix it without reading the source.
#include <stdexcept>
#include <string>

namespace cutaway {

class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class InputError : public Error {
public:
    using Error::Error;
};

class RuntimeError : public Error {
public:
    using Error::Error;
};

class ResourceError : public RuntimeError {
public:
    using RuntimeError::RuntimeError;
};

} // namespace cutaway
