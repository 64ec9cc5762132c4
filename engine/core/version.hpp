#pragma once

namespace ashlar {
// "MAJOR.MINOR.PATCH" of the engine and its Lua API.
const char* version();
}  // namespace ashlar
