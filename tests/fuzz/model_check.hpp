#pragma once
// A model a reader accepted must give finite values (never NaN) at a point,
// or be refused with a meridian::Error by the engine.

#include "fuzz_support.hpp"
#include "meridian/gravity/gravity_field.hpp"
#include "meridian/gravity/gravity_model.hpp"

namespace meridian_fuzz {

inline void check_model(const meridian::gravity::GravityModelData& m) {
  check_finite(m.gm_m3_s2, "GM not finite");
  check_finite(m.radius_m, "reference radius not finite");
  if (m.coefficients.max_degree() > 60) return;  // the input's size bounds it; keep each run fast
  expect_value_or_error([&] {
    const meridian::gravity::GravityField field(m, {false, 1});
    const auto v = field.evaluate({0.7, 0.3, 100.0});
    check_finite(v.xi_rad, "xi is NaN or infinite");
    check_finite(v.eta_rad, "eta is NaN or infinite");
    check_finite(v.geoid_m, "N is NaN or infinite");
  });
}

}  // namespace meridian_fuzz
