// Loads one .egm model once and exits: a whole fresh process, so that the first touch of the
// coefficient arrays (page faults) is counted as a user meets it, which a loop inside one
// process hides by reusing freed memory. Built twice, against Meridian and against
// GeographicLib (the reference); bench/load_timing.sh runs them alternately under perf stat.
//   load_model_once_meridian DIR NAME     load_model_once_geographiclib DIR NAME
#include <cstdio>
#include <string>

#ifdef MERIDIAN_LOAD_REFERENCE
#include <GeographicLib/GravityModel.hpp>
#else
#include "meridian/gravity/gravity_field.hpp"
#include "meridian/io/gravity_egm.hpp"
#endif

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s DIR NAME (loads DIR/NAME.egm and its .cof)\n", argv[0]);
    return 2;
  }
#ifdef MERIDIAN_LOAD_REFERENCE
  const GeographicLib::GravityModel g(argv[2], argv[1]);
  std::printf("%d\n", g.Degree());
#else
  const meridian::gravity::GravityField f(meridian::io::read_egm_file(std::string(argv[1]) + "/" + argv[2] + ".egm"));
  std::printf("%d\n", f.max_degree());
#endif
  return 0;
}
