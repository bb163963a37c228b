#pragma once
/// \file version.hpp
/// The version of the Meridian library (CMake project version), as named in
/// reports, `meridian --version` and file headers.

namespace meridian {

/// e.g. "0.1.0".
const char* version() noexcept;

}  // namespace meridian
