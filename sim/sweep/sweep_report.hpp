// What a finished sweep writes into DIR, from the point files alone (so the local runner and
// --collect after a Slurm array write the same bytes):
//   results.csv   one row per point in point order: a column per key, then scene, filter and the
//                 result columns of result_columns() (RFC 4180 quoting, fixed decimals)
//   columns.json  every column's name, unit and meaning (the plot script labels axes from it)
//   summary.md    what was swept, the golden-compare verdict, the plots, the best points, every row
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/sweep/sweep_spec.hpp"

namespace tfu::sweep {

// How a result column is held in a point file's "result" object (what --collect and a resumed run
// check before reading it): None, the column is not in "result" (point, error).
enum class ResultType { None, Number, NumberOrInf, Bool, NumberOrNull };  // NumberOrNull: null (empty in the CSV) where the model has no figure

struct Column {
  std::string name, unit, meaning;
  ResultType type = ResultType::None;
};
// The columns after the keys, scene and filter.
const std::vector<Column>& result_columns();
// Every column of results.csv, keys first.
std::vector<Column> csv_columns(const Spec& spec);

// A point's file DIR/points/ID.json as a resumed run and --collect read it, through the input checks
// (cmodel/input_file.hpp: a regular file, at most 64 MiB). nullopt, the point is not done and runs
// (again): the file is absent, is not JSON (a write cut short), or is not marked "complete": true.
// A file marked complete is checked like a spec, and InputError names the file and the key: "point"
// with this point's "id"; then a one-line string "error", or a "result" object with every result
// column of its type (result_columns()).
std::optional<nlohmann::json> read_point_file(const std::string& dir, const Point& p);
// read_point_file(dir, p) holds a result.
bool point_done(const std::string& dir, const Point& p);

// Reads every point's file from DIR/points/ (read_point_file); CheckFailed naming the missing points
// (at most a few, and how many) if any is absent or incomplete.
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
