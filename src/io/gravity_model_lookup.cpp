#include "meridian/io/gravity_model_lookup.hpp"

#include <cstdlib>
#include <system_error>

#include "meridian/core/error.hpp"
#include "meridian/io/gravity_egm.hpp"
#include "meridian/io/gravity_icgem.hpp"
#include "gravity_text.hpp"

namespace meridian::io {
namespace fs = std::filesystem;

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
  if (detail::lower(name_or_path).ends_with(".egm.cof")) p.replace_extension();  // X.egm.cof → X.egm
  if (fs::is_regular_file(p, ec)) return p;
  const bool looks_like_path = name_or_path.find('/') != std::string::npos || p.has_extension();
  if (!looks_like_path) {
    const std::string want = detail::lower(name_or_path);
    for (const fs::path& dir : gravity_search_path()) {
      if (!fs::is_directory(dir, ec)) continue;
      for (const char* ext : {".egm", ".gfc"}) {
        for (const auto& entry : fs::directory_iterator(dir, ec)) {
          const fs::path& f = entry.path();
          if (detail::lower(f.extension().string()) == ext && detail::lower(f.stem().string()) == want &&
              entry.is_regular_file(ec))
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

gravity::GravityModelData load_model(const std::string& name_or_path, const gravity::Truncation& truncation) {
  const fs::path p = resolve_model(name_or_path);
  const std::string ext = detail::lower(p.extension().string());
  if (ext == ".egm") return read_egm_file(p, truncation);
  if (ext == ".gfc") return read_icgem_file(p, truncation);
  throw InputError("unknown gravity model format \"" + p.extension().string() + "\" (expected .gfc or .egm)",
                   {p.string(), {}, ""});
}

}  // namespace meridian::io
