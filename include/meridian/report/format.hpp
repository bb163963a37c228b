#pragma once
/// \file format.hpp
/// How angles and σ are printed in every workflow's reports (text, HTML):
/// in the field book's angle unit (DMS by default), σ and corrections in
/// arc-seconds (mgon for gon books), "n/a" for what cannot be stated.

#include <cmath>
#include <string>

#include <fmt/format.h>

#include "meridian/core/dms.hpp"
#include "meridian/core/units.hpp"

namespace meridian::report {

/// How a report writes angles, in the unit the field book was booked in
/// (its `angle_unit:`):
///
/// | book     | directions and angles        | σ and small corrections |
/// |----------|------------------------------|-------------------------|
/// | dms      | 218°39'29.2"                 | 7.0", +3.26"            |
/// | deg      | 218.658111°                  | 7.0", +3.26"            |
/// | gon      | 242.953456 gon               | 2.16 mgon, +1.01 mgon   |
/// | ddd.mmss | 218.39292 (calculator form)  | 7.0", +3.26"            |
///
/// `decimals` always counts the digits of arc-seconds a DMS book would show;
/// the other units show the same resolution (4 more digits of degrees or
/// gon, one more of mgon than of arc-seconds).
class AngleFormat {
 public:
  explicit AngleFormat(AngleUnit unit = AngleUnit::Dms) : unit_(unit) {}
  AngleUnit unit() const { return unit_; }

  /// A direction in [0, 360°).
  std::string dir(double rad, int decimals = 1) const {
    const Angle a = Angle::radians(rad);
    switch (unit_) {
      case AngleUnit::Degrees: return fmt::format("{:.{}f}\u00b0", a.normalized_positive().deg(), decimals + 4);
      case AngleUnit::Gon: return fmt::format("{:.{}f} gon", a.normalized_positive().gon(), decimals + 4);
      case AngleUnit::DddMmss: return format_ddd_mmss(a.normalized_positive(), decimals);
      case AngleUnit::Dms: break;
    }
    return format_direction_dms(a, {decimals, true, false});
  }
  /// A signed angle (a convergence, a clamp offset).
  std::string dms(double rad, int decimals = 2) const {
    const Angle a = Angle::radians(rad);
    switch (unit_) {
      case AngleUnit::Degrees: return fmt::format("{:+.{}f}\u00b0", a.deg(), decimals + 4);
      case AngleUnit::Gon: return fmt::format("{:+.{}f} gon", a.gon(), decimals + 4);
      case AngleUnit::DddMmss: return (rad < 0 ? "-" : "+") + format_ddd_mmss(Angle::radians(std::fabs(rad)), decimals);
      case AngleUnit::Dms: break;
    }
    return format_dms(a, {decimals, true, true});
  }
  /// A σ, "n/a" when not finite.
  std::string sig(double rad, int decimals = 1) const {
    if (!std::isfinite(rad)) return "n/a";
    return unit_ == AngleUnit::Gon ? fmt::format("{:.{}f} mgon", rad / units::kGon * 1000.0, decimals + 1)
                                   : fmt::format("{:.{}f}\"", rad / units::kArcsecond, decimals);
  }
  /// A small signed correction.
  std::string sec(double rad, int decimals = 2) const {
    return unit_ == AngleUnit::Gon ? fmt::format("{:+.{}f} mgon", rad / units::kGon * 1000.0, decimals + 1)
                                   : fmt::format("{:+.{}f}\"", rad / units::kArcsecond, decimals);
  }

 private:
  AngleUnit unit_;
};

}  // namespace meridian::report

namespace meridian::report::fmtx {

/// A plain number, "n/a" when not finite.
inline std::string num(double v, int decimals) {
  return std::isfinite(v) ? fmt::format("{:.{}f}", v, decimals) : std::string("n/a");
}

}  // namespace meridian::report::fmtx
