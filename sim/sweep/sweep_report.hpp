// What a finished sweep writes into DIR, from the point files alone (so the local runner and
// --collect after a Slurm array write the same bytes):
//   results.csv   one row per point in point order: a column per key, then scene, filter and the
//                 result columns of result_columns() (RFC 4180 quoting, fixed decimals)
//   columns.json  every column's name, unit and meaning (the plot script labels axes from it)
//   summary.md    what was swept, the golden-compare verdict, the plots, the best points, every row
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/sweep/sweep_spec.hpp"

namespace tfu::sweep {

struct Column {
  std::string name, unit, meaning;
};
// The columns after the keys, scene and filter.
const std::vector<Column>& result_columns();
// Every column of results.csv, keys first.
std::vector<Column> csv_columns(const Spec& spec);

// Reads every point's file from DIR/points/; CheckFailed naming the missing points (at most a few,
// and how many) if any is absent or incomplete.
std::vector<nlohmann::json> read_point_files(const std::string& dir, const std::vector<Point>& points);

std::string results_csv(const Spec& spec, const std::vector<Point>& points, const std::vector<nlohmann::json>& files);
std::string columns_json(const Spec& spec);

// A chart of the summary: its file (relative to DIR) and caption.
struct Plot {
  std::string file, caption;
};
std::string summary_markdown(const Spec& spec, const std::vector<Point>& points, const std::vector<nlohmann::json>& files,
                             const std::vector<Plot>& plots);

// Points whose golden compare failed or that could not run.
size_t failed_points(const std::vector<nlohmann::json>& files);

}  // namespace tfu::sweep
