#pragma once
/// \file method.hpp
/// The track solutions a navigation run computes side by side (docs/navigation.md).
#include <array>
#include <string>
#include <string_view>

namespace meridian::nav {

/// A method of the navigation workflow. The string names are those of the JSON output and
/// the configuration (`methods:`).
enum class Method {
  DeadReckoning,      ///< "dead-reckoning": DR from the initial position, no observation
  SequentialNoBias,   ///< "sequential-no-bias": spec §4, DR carried without bias correction
  SequentialBiasI,    ///< "sequential-bias-I": §4.1 method I (running mean of the bias)
  SequentialBiasII,   ///< "sequential-bias-II": §4.1 method II (segments)
  Backward,           ///< "backward": §4.2, bias-I forward combined with a backward window
  FixClosure,         ///< "fix-closure": §5, bias-I forward with each fix's closure
                      ///< distributed linearly over the segment before it
  Ekf,                ///< "ekf": §6, extended Kalman filter with the velocity bias in the state
  Rts,                ///< "rts": §6, Rauch–Tung–Striebel smoother of the EKF over the line
};

inline constexpr std::array<Method, 8> kAllMethods = {
    Method::DeadReckoning, Method::SequentialNoBias, Method::SequentialBiasI,
    Method::SequentialBiasII, Method::Backward, Method::FixClosure, Method::Ekf, Method::Rts};

/// "dead-reckoning", "sequential-no-bias", … (the names above).
std::string to_string(Method m);
/// The method of a name above (exact spelling). Throws InputError otherwise.
Method method_from_string(std::string_view name);

}  // namespace meridian::nav
