#include "meridian/nav/method.hpp"

#include "meridian/core/error.hpp"

namespace meridian::nav {

namespace {
constexpr std::array<std::string_view, kAllMethods.size()> kMethodNames = {
    "dead-reckoning", "sequential-no-bias", "sequential-bias-I", "sequential-bias-II",
    "backward",       "fix-closure",        "ekf",               "rts"};
}  // namespace

std::string to_string(Method m) { return std::string(kMethodNames[static_cast<std::size_t>(m)]); }

Method method_from_string(std::string_view name) {
  for (std::size_t i = 0; i < kMethodNames.size(); ++i)
    if (kMethodNames[i] == name) return kAllMethods[i];
  std::string known;
  for (const auto n : kMethodNames) known += (known.empty() ? "" : ", ") + std::string(n);
  throw InputError("unknown navigation method \"" + std::string(name) + "\" (known: " + known + ")");
}

}  // namespace meridian::nav
