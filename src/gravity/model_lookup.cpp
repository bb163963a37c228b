#include "meridian/gravity/model_lookup.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <system_error>

#include "meridian/core/error.hpp"
#include "meridian/gravity/egm_format.hpp"
#include "meridian/gravity/icgem.hpp"

namespace meridian::gravity {
namespace fs = std::filesystem;
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

}  // namespace

std::vector<fs::path> gravity_search_path() {
  std::vector<fs::path> dirs;
  const char* gp = std::getenv("GEOGRAPHICLIB_GRAVITY_PATH");
  const char* dp = std::getenv("GEOGRAPHICLIB_DATA");
  if (gp && *gp) dirs.emplace_back(gp);
  else if (dp && *dp) dirs.emplace_back(fs::path(dp) / "gravity");
  dirs.emplace_back("/usr/share/GeographicLib/gravity");
  dirs.emplace_back("/usr/local/share/GeographicLib/gravity");
  return dirs;
}

fs::path resolve_model(const std::string& name_or_path) {
  if (name_or_path.empty()) throw InputError("no gravity model given", {"", {}, "--model"});
  std::error_code ec;
  fs::path p(name_or_path);
  if (ends_with(lower(name_or_path), ".egm.cof")) p.replace_extension();  // X.egm.cof → X.egm
  if (fs::is_regular_file(p, ec)) return p;
  const bool looks_like_path = name_or_path.find('/') != std::string::npos || p.has_extension();
  if (!looks_like_path) {
    const std::string want = lower(name_or_path);
    for (const fs::path& dir : gravity_search_path()) {
      if (!fs::is_directory(dir, ec)) continue;
      for (const char* ext : {".egm", ".gfc"}) {
        for (const auto& entry : fs::directory_iterator(dir, ec)) {
          const fs::path& f = entry.path();
          if (lower(f.extension().string()) == ext && lower(f.stem().string()) == want && entry.is_regular_file(ec))
            return f;
        }
      }
    }
  }
  std::string searched;
  for (const fs::path& d : gravity_search_path()) searched += (searched.empty() ? "" : ", ") + d.string();
  throw InputError("gravity model \"" + name_or_path + "\" not found: no such file, and no NAME.egm or NAME.gfc in " +
                       searched + " (install one with geographiclib-get-gravity, or set GEOGRAPHICLIB_GRAVITY_PATH)",
                   {"", {}, "--model"});
}

GravityModelData load_model(const std::string& name_or_path, const Truncation& truncation) {
  const fs::path p = resolve_model(name_or_path);
  const std::string ext = lower(p.extension().string());
  if (ext == ".egm") return read_egm_file(p, truncation);
  if (ext == ".gfc") return read_icgem_file(p, truncation);
  throw InputError("unknown gravity model format \"" + p.extension().string() + "\" (expected .gfc or .egm)",
                   {p.string(), {}, ""});
}

}  // namespace meridian::gravity
