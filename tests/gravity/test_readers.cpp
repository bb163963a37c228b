// Readers and writers: round trips, real files (when ../shared is present),
// and bad input rejected with the file and line named.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <vector>

#include "gravity_test_support.hpp"
#include "meridian/core/atomic_file.hpp"
#include "meridian/core/error.hpp"
#include "meridian/gravity/gravity_field.hpp"
#include "meridian/io/gravity_model_lookup.hpp"

namespace {

using namespace gtest_gravity;
using meridian::gravity::GravityModelData;
using meridian::io::read_egm_file;
using meridian::io::read_icgem_file;

fs::path write_text(const std::string& name, const std::string& text) {
  const fs::path p = scratch_dir() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

const char* kHead =
    "some free text\nbegin_of_head\nproduct_type gravity_field\nmodelname tiny\nearth_gravity_constant 3.986004415D+14\n"
    "radius 6378136.3\nmax_degree 3\nnorm fully_normalized\ntide_system tide_free\nerrors no\nkey L M C S\nend_of_head\n";
const char* kBody =
    "gfc 0 0 1.0d0 0.0\n"
    "gfc 2 0 -4.8D-4 0\ngfc 2 1 1e-9 2e-9\ngfc 2 2 2.4e-6 -1.4e-6\n"
    "gfc 3 0 9.5e-7 0\ngfc 3 1 2e-6 2.4e-7\ngfc 3 2 9e-7 -6e-7\ngfc 3 3 7e-7 1.4e-6 1e-12 1e-12\n";

// Expect `f` to throw a ParseError whose text names the file, the line (if
// > 0) and contains `fragment`.
template <class F>
void expect_parse_error(F f, const fs::path& file, int line, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "no error for " << fragment;
  } catch (const meridian::InputError& e) {
    const std::string w = e.what();
    EXPECT_NE(w.find(file.filename().string()), std::string::npos) << w;
    if (line > 0) {
      EXPECT_EQ(e.context().line, line) << w;
    }
    EXPECT_NE(w.find(fragment), std::string::npos) << w;
  }
}

TEST(IcgemReader, ParsesFortranExponentsAndOmittedDegreeOne) {
  const fs::path p = write_text("tiny.gfc", std::string(kHead) + kBody);
  const GravityModelData m = read_icgem_file(p);
  EXPECT_EQ(m.name, "tiny");
  EXPECT_EQ(m.gm_m3_s2, 3.986004415e14);
  EXPECT_EQ(m.coefficients.max_degree(), 3);
  EXPECT_EQ(m.coefficients.c(2, 0), -4.8e-4);
  EXPECT_EQ(m.coefficients.s(3, 3), 1.4e-6);
  EXPECT_EQ(m.coefficients.c(1, 1), 0.0);
  const GravityModelData t = read_icgem_file(p, {2, 1});
  EXPECT_EQ(t.coefficients.max_degree(), 2);
  EXPECT_EQ(t.coefficients.max_order(), 1);
  EXPECT_EQ(t.coefficients.size(), 5u);  // (0,0) (1,0) (2,0) (1,1) (2,1)
}

TEST(IcgemReader, RejectsBadFilesNamingTheLine) {
  const std::string head = kHead;  // 12 lines; data start on line 13
  auto bad = [&](const std::string& name, const std::string& text, int line, const std::string& fragment) {
    const fs::path p = write_text(name, text);
    expect_parse_error([&] { (void)read_icgem_file(p); }, p, line, fragment);
  };
  bad("dup.gfc", head + kBody + "gfc 2 1 0 0\n", 21, "duplicate coefficient (n, m) = (2, 1), first given on line 15");
  bad("deg.gfc", head + kBody + "gfc 4 0 0 0\n", 21, "exceeds the header's max_degree 3");
  bad("nan.gfc", head + "gfc 2 0 -4.8x-4 0\n", 13, "C is not a number");
  bad("short.gfc", head + "gfc 2 0\n", 13, "expected at least 5");
  bad("mgtn.gfc", head + "gfc 2 3 0 0\n", 13, "invalid (n, m) = (2, 3)");
  bad("tv.gfc", head + "gfct 2 0 1 0 20000101\n", 13, "time-variable record");
  bad("missing.gfc", head + "gfc 2 0 1 0\ngfc 2 1 0 0\n", 0, "missing coefficient (n, m) = (2, 2)");
  std::string unnorm = kHead;
  unnorm.replace(unnorm.find("fully_normalized"), 16, "unnormalized");
  bad("norm.gfc", unnorm + kBody, 8, "normalisation \"unnormalized\" is not supported");
  bad("nohead.gfc", "gfc 0 0 1 0\n", 0, "no end_of_head");
  std::string nogm = kHead;
  nogm.replace(nogm.find("earth_gravity_constant"), 22, "earth_gravity_konstant");
  bad("nogm.gfc", nogm + kBody, 12, "no earth_gravity_constant");
  EXPECT_THROW((void)read_icgem_file(scratch_dir() / "does_not_exist.gfc"), meridian::IoError);
}

// A header's degree is checked against the file's size before anything is
// allocated: 10^9 would need 5·10^17 coefficients (8·10^18 bytes).
TEST(IcgemReader, HugeDegreeInTheHeaderIsAnInputErrorNotAnAllocation) {
  std::string huge = kHead;
  huge.replace(huge.find("max_degree 3"), 12, "max_degree 1000000000");
  const fs::path p = write_text("huge.gfc", huge + kBody);
  expect_parse_error([&] { (void)read_icgem_file(p); }, p, 12, "max_degree 1000000000 cannot be right");
  try {
    (void)read_icgem_file(p);
  } catch (const meridian::InputError& e) {
    EXPECT_EQ(e.context().field, "max_degree");
  }
  // Truncated on load, the same file is read as far as it is complete.
  EXPECT_EQ(read_icgem_file(p, {3, -1}).coefficients.max_degree(), 3);
  // The bound is the shortest possible file: one that just holds it passes it
  // (and is then read normally); one byte less fails before allocation.
  std::string min = kHead;
  min.replace(min.find("max_degree 3"), 12, "max_degree 2");
  const std::string body = "gfc 2 0 0 0\ngfc 2 1 0 0\ngfc 2 2 0 0";
  EXPECT_NO_THROW((void)read_icgem_file(write_text("min.gfc", min + body)));
}

// Fully normalised coefficients are at most 1 in absolute value; a larger one
// is a damaged file, not a model to evaluate (fuzz_egm found NaN from one).
TEST(IcgemReader, CoefficientsBeyondOneAreRejected) {
  std::string body = kBody;
  body.replace(body.find("gfc 3 1 2e-6"), 12, "gfc 3 1 2e+6");
  const fs::path p = write_text("big.gfc", std::string(kHead) + body);
  expect_parse_error([&] { (void)read_icgem_file(p); }, p, 18, "C = 2e+06 is not a fully normalised coefficient");
}

// The engine's last line of defence: a model whose values overflow is a
// NumericalError, never NaN or infinity in an output.
TEST(GravityFieldGuard, NonFiniteValuesAreANumericalError) {
  GravityModelData m = read_icgem_file(write_text("ok.gfc", std::string(kHead) + kBody));
  m.coefficients.set(3, 1, 1e305, 1e305);  // times GM/a ≈ 6e7: beyond the largest double
  const meridian::gravity::GravityField field(m, {false, 1});
  EXPECT_THROW((void)field.evaluate({0.5, 0.2, 0}), meridian::NumericalError);
  const std::vector<meridian::gravity::GeodeticPoint> pts(5, {0.5, 0.2, 0});
  EXPECT_THROW((void)field.evaluate(pts), meridian::NumericalError);
}

TEST(IcgemReader, HeaderTextMustBeUtf8AndMetadataIsKeptAsStated) {
  std::string latin1 = kHead;
  latin1.replace(latin1.find("modelname tiny"), 14, "modelname t\xE9st");
  const fs::path p = write_text("latin1.gfc", latin1 + kBody);
  expect_parse_error([&] { (void)read_icgem_file(p); }, p, 4, "modelname is not UTF-8 text (byte 0xE9 at position 2)");
  std::string utf8 = kHead;
  utf8.replace(utf8.find("modelname tiny"), 14, "modelname t\xC3\xA9st");
  const GravityModelData ok = read_icgem_file(write_text("utf8.gfc", utf8 + kBody));
  EXPECT_EQ(ok.name, "t\xC3\xA9st");
  EXPECT_EQ(ok.tide_system, "tide_free");
  EXPECT_EQ(ok.normalization, "fully_normalized");
  // Keys left out: nothing is invented.
  std::string bare = kHead;
  for (const char* line : {"norm fully_normalized\n", "tide_system tide_free\n"}) bare.erase(bare.find(line), std::strlen(line));
  const GravityModelData b = read_icgem_file(write_text("bare.gfc", bare + kBody));
  EXPECT_EQ(b.tide_system, "");
  EXPECT_EQ(b.normalization, "");
}

TEST(EgmFormat, WriteReadRoundTripIsExactAndMatchesIcgem) {
  meridian::gravity::SyntheticModelOptions o;
  o.max_degree = 50;
  o.seed = 77;
  const GravityModelData m = meridian::gravity::make_synthetic_model(o);
  meridian::io::write_egm_files(m, scratch_dir() / "rt");
  meridian::write_file_atomically(scratch_dir() / "rt.gfc", meridian::io::format_icgem(m));
  const GravityModelData e = read_egm_file(scratch_dir() / "rt.egm");
  const GravityModelData g = read_icgem_file(scratch_dir() / "rt.gfc");
  EXPECT_EQ(e.coefficients.c_values(), m.coefficients.c_values());
  EXPECT_EQ(e.coefficients.s_values(), m.coefficients.s_values());
  EXPECT_EQ(g.coefficients.c_values(), m.coefficients.c_values());
  EXPECT_EQ(g.coefficients.s_values(), m.coefficients.s_values());
  EXPECT_EQ(e.gm_m3_s2, m.gm_m3_s2);
  EXPECT_EQ(e.radius_m, m.radius_m);
  EXPECT_DOUBLE_EQ(e.reference.flattening, m.reference.flattening);
  // Same seed, same model; another seed, another model.
  EXPECT_EQ(meridian::gravity::make_synthetic_model(o).coefficients.c_values(), m.coefficients.c_values());
  o.seed = 78;
  EXPECT_NE(meridian::gravity::make_synthetic_model(o).coefficients.c_values(), m.coefficients.c_values());
  // Truncated read of the binary file.
  const GravityModelData t = read_egm_file(scratch_dir() / "rt.egm", {20, 7});
  EXPECT_EQ(t.coefficients.c_values(), m.coefficients.truncated(20, 7).c_values());
  EXPECT_EQ(t.coefficients.s_values(), m.coefficients.truncated(20, 7).s_values());
}

TEST(EgmFormat, RejectsDamagedFiles) {
  meridian::gravity::SyntheticModelOptions o;
  o.max_degree = 10;
  const GravityModelData m = meridian::gravity::make_synthetic_model(o);
  meridian::io::write_egm_files(m, scratch_dir() / "dmg");
  const std::string meta = slurp(scratch_dir() / "dmg.egm"), cof = slurp(scratch_dir() / "dmg.egm.cof");
  const fs::path egm = scratch_dir() / "bad.egm", bcof = scratch_dir() / "bad.egm.cof";
  auto expect = [&](const std::string& meta_text, const std::string& cof_bytes, const fs::path& named, const std::string& frag) {
    write_text("bad.egm", meta_text);
    write_text("bad.egm.cof", cof_bytes);
    expect_parse_error([&] { (void)read_egm_file(egm); }, named, 0, frag);
  };
  expect(meta, cof.substr(0, cof.size() - 100), bcof, "file truncated");
  expect(meta, cof + "junk", bcof, "extra data");
  std::string other_id = cof;
  other_id[0] = 'Q';
  expect(meta, other_id, bcof, "ID mismatch");
  expect("EGMF-2\n" + meta.substr(7), cof, egm, "unsupported .egm version");
  std::string nomass = meta;
  nomass.replace(nomass.find("ModelMass"), 9, "ModelMuss");
  expect(nomass, cof, egm, "ModelMass");
  std::string c00 = cof;
  const double one = 1.0;
  std::memcpy(c00.data() + 16, &one, 8);
  expect(meta, c00, bcof, "degree 0 coefficient must be 0");
  // A .cof claiming degree and order 100000 (4·10^10 bytes of coefficients)
  // in a short file: truncated, found before allocating.
  std::string huge = cof.substr(0, 8);
  const std::int32_t nm[2] = {100000, 100000};
  huge.append(reinterpret_cast<const char*>(nm), sizeof nm);
  huge += cof.substr(16);
  expect(meta, huge, bcof, "file truncated: gravitational needs 80001600008 bytes");
  // Found by fuzz_egm: a coefficient of -9.6e301 gave N = NaN and xi = 4.7e307 arcsec.
  std::string big = cof;
  const double beyond = -9.6e301;
  std::memcpy(big.data() + 16 + 8 * 5, &beyond, 8);
  expect(meta, big, bcof, "coefficient C(5, 0) = -9.6e+301 of the gravitational set is not a fully normalised");
  // A NaN among the S̄ (the last value of the file's S̄ columns: m = 10, n = 10), whole and
  // truncated reads (the reader scans each chunk or kept column as it reads it).
  std::string nan_s = cof;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::memcpy(nan_s.data() + nan_s.size() - 8 - 8, &nan, 8);  // before the correction set's N = M = −1
  expect(meta, nan_s, bcof, "non-finite coefficient S(10, 10) (nan) of the gravitational set");
  // Every position of both blocks, every kind of bad value: the scan goes eight at a time in
  // vectors and the rest one at a time, and must find each and name it.
  {
    const int n_max = m.coefficients.max_degree();
    std::vector<std::string> names;  // the file's order: C̄ columns m = 0…N, then S̄ columns m = 1…N
    for (int mm = 0; mm <= n_max; ++mm)
      for (int nn = mm; nn <= n_max; ++nn) names.push_back(fmt::format("C({}, {})", nn, mm));
    for (int mm = 1; mm <= n_max; ++mm)
      for (int nn = mm; nn <= n_max; ++nn) names.push_back(fmt::format("S({}, {})", nn, mm));
    const double bad_values[] = {std::numeric_limits<double>::quiet_NaN(), -std::numeric_limits<double>::infinity(),
                                 1.5, -1.0000001};
    for (std::size_t k = 1; k < names.size(); ++k)  // C̄00 has its own check
      for (const double b : bad_values) {
        std::string damaged = cof;
        std::memcpy(damaged.data() + 16 + 8 * k, &b, 8);
        SCOPED_TRACE(testing::Message() << names[k] << " = " << b);
        expect(meta, damaged, bcof, "coefficient " + names[k]);
      }
  }
  write_text("bad.egm", meta);
  write_text("bad.egm.cof", big);
  expect_parse_error([&] { (void)read_egm_file(egm, {8, 8}); }, bcof, 0, "coefficient C(5, 0) = -9.6e+301");
  write_text("bad.egm.cof", nan_s);
  EXPECT_NO_THROW((void)read_egm_file(egm, {9, 9}));  // the NaN is in a column not kept
  // A correction set (metres) with a coefficient beyond 1000 m is a damaged file: it gave
  // geoid heights of 1e300 m and a .gtx full of inf (trial finding).
  GravityModelData wc = m;
  wc.correction = meridian::gravity::GeoidCorrection{meridian::gravity::SphericalHarmonicCoefficients(2, 2), 1.0, 0.0};
  wc.correction->coefficients.set(1, 1, 0.5, 1e300);
  meridian::io::write_egm_files(wc, scratch_dir() / "corr");
  expect_parse_error([&] { (void)read_egm_file(scratch_dir() / "corr.egm"); }, scratch_dir() / "corr.egm.cof", 0,
                     "coefficient S(1, 1) = 1e+300 m of the correction set is beyond 1000 m");
  wc.correction->coefficients.set(1, 1, 0.5, 2.5);
  meridian::io::write_egm_files(wc, scratch_dir() / "corr");
  EXPECT_NO_THROW((void)read_egm_file(scratch_dir() / "corr.egm"));
  std::string latin1 = meta;
  latin1.replace(latin1.find("Description"), 11, "Description caf\xE9");
  expect(latin1, cof, egm, "Description is not UTF-8 text");
}

TEST(ModelLookup, FindsModelsByNameInGeographicLibDirectories) {
  const std::string name = synthetic_files(20);
  ::setenv("GEOGRAPHICLIB_GRAVITY_PATH", scratch_dir().c_str(), 1);
  EXPECT_EQ(meridian::io::resolve_model(name), scratch_dir() / (name + ".egm"));
  EXPECT_EQ(meridian::io::resolve_model((scratch_dir() / (name + ".egm.cof")).string()),
            scratch_dir() / (name + ".egm"));
  EXPECT_EQ(meridian::io::load_model(name).coefficients.max_degree(), 20);
  try {
    (void)meridian::io::resolve_model("no_such_model_xyz");
    FAIL();
  } catch (const meridian::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(scratch_dir().string()), std::string::npos) << e.what();
  }
  ::unsetenv("GEOGRAPHICLIB_GRAVITY_PATH");
}

TEST(RealModels, SharedIcgemFilesParseWhenAvailable) {
  const fs::path dir = shared_gravity_dir();
  if (!fs::exists(dir / "EGM2008_to120.gfc") || !fs::exists(dir / "GGM05S.gfc"))
    GTEST_SKIP() << "../shared/data/gravity not present (optional data)";
  const GravityModelData e = read_icgem_file(dir / "EGM2008_to120.gfc");
  EXPECT_EQ(e.coefficients.max_degree(), 120);
  EXPECT_EQ(e.coefficients.c(0, 0), 1.0);
  EXPECT_EQ(e.coefficients.c(2, 0), -0.484165143790815e-03);
  const GravityModelData g = read_icgem_file(dir / "GGM05S.gfc", {60, -1});
  EXPECT_EQ(g.coefficients.max_degree(), 60);
  EXPECT_EQ(g.tide_system, "zero_tide");
  EXPECT_NEAR(g.coefficients.c(2, 0), -4.8417e-4, 1e-7);
  if (fs::exists(dir / "egm96.gfc") && fs::exists(dir / "egm96.egm")) {
    const GravityModelData a = read_icgem_file(dir / "egm96.gfc"), b = read_egm_file(dir / "egm96.egm");
    EXPECT_EQ(a.coefficients.c_values(), b.coefficients.c_values());
    EXPECT_EQ(a.coefficients.s_values(), b.coefficients.s_values());
  }
}

}  // namespace
