#include "meridian/core/version.hpp"

namespace meridian {

const char* version() noexcept { return MERIDIAN_VERSION; }

}  // namespace meridian
