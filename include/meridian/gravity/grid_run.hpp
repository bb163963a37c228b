#pragma once
/// \file grid_run.hpp
/// The Result of a `gravity grid` run (issue 14): what was synthesised, with which model and
/// path, and where it was written — everything the run's summary writers
/// (report/gravity_text.hpp gravity_grid_text, report/gravity_json.hpp gravity_grid_to_json)
/// show. Built by io::run_gravity_grid (io/gravity_jobs.hpp); the grid's values went to the
/// file row by row (io/gravity_grid_files.hpp).

#include <string>
#include <vector>

#include "meridian/gravity/grid_spec.hpp"
#include "meridian/gravity/grid_synthesis.hpp"
#include "meridian/gravity/points.hpp"

namespace meridian::gravity {

/// How one quantity is stored in the output file, as the file names it.
struct GridFileQuantity {
  std::string name;       ///< variable / column name: xi, eta, geoid, anomaly, dg_east, dg_north, dg_up
  std::string units;      ///< "arcsec", "m" or "mGal"
  std::string long_name;  ///< definition and sign convention, one line
};

/// `gravity grid`: the grid written and how it was made.
struct GridRunResult {
  std::string output;        ///< the file written
  std::string format;        ///< "netcdf", "csv" or "gtx"
  std::string format_label;  ///< "NetCDF", "CSV" or "GTX"
  ModelInfo model;           ///< the model, as its file states it
  /// The grid as run: region, spacing (degrees), registration, height, quantities. Its
  /// node_heights is empty (the height file is closed); height_grid says where they came from.
  GridSpec spec;
  std::string height_grid;   ///< FILE.nc[?VAR] of per-node heights; empty: every node at spec.height_m
  std::vector<GridFileQuantity> quantities;  ///< spec.quantities in order, as stored
  GridSynthesisResult synthesis;             ///< rows, columns, path used, FFT length, threads
  /// Longitude columns the file holds: synthesis.columns, less the repeated column at W + 360°
  /// that a global gridline .gtx leaves out (its readers wrap longitudes).
  std::size_t stored_columns = 0;
  double elapsed_s = 0;      ///< wall time of the synthesis and the write (s)
};

}  // namespace meridian::gravity
