#pragma once
// Private to the maglev module (not installed): error context of its numerics.

#include <optional>
#include <string>

#include "meridian/core/error.hpp"

namespace meridian::maglev::detail {

/// Context naming only the input field; the reader adds file and line.
inline ErrorContext at(const std::string& field) { return ErrorContext{{}, std::nullopt, field}; }

}  // namespace meridian::maglev::detail
