# Locates the netCDF C library (Debian: libnetcdf-dev) and provides the imported target
# NetCDF::netcdf. Used privately by Meridian::io_gravity (the grid writer); installed beside
# MeridianConfig.cmake because a static Meridian::io_gravity still names it for the link.
find_path(NetCDF_INCLUDE_DIR netcdf.h)
find_library(NetCDF_LIBRARY NAMES netcdf)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(NetCDF REQUIRED_VARS NetCDF_LIBRARY NetCDF_INCLUDE_DIR)
if(NetCDF_FOUND AND NOT TARGET NetCDF::netcdf)
  add_library(NetCDF::netcdf UNKNOWN IMPORTED)
  set_target_properties(NetCDF::netcdf PROPERTIES
    IMPORTED_LOCATION "${NetCDF_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${NetCDF_INCLUDE_DIR}")
endif()
mark_as_advanced(NetCDF_INCLUDE_DIR NetCDF_LIBRARY)
