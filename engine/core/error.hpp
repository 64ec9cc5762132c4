// Exception types thrown by the engine. Bindings convert each to a Lua error;
// outcomes such as "unstable" are never exceptions (they are result statuses).
#pragma once

#include <stdexcept>
#include <string>

namespace ashlar {

// Base of every ashlar exception.
class Error : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// A value outside its allowed range or shape (the message says which and why).
class InvalidArgument : public Error {
public:
  using Error::Error;
};

// Geometry that is not a valid block: open, self-intersecting, inverted,
// degenerate or with non-planar faces. The message names the defect.
class GeometryError : public Error {
public:
  using Error::Error;
};

// A file that cannot be read, parsed or written.
class IoError : public Error {
public:
  using Error::Error;
};

}  // namespace ashlar
