// tfu sweep: design-space exploration (docs/design-space.md). A spec's points (grid of unit
// configuration and sampler keys x scenes x filters, plus explicit points) run with the golden
// compare, on the local runner (all cores, resumable) or as a Slurm job array; results.csv,
// summary.md and, with --plot, charts. `tfu plot` draws further charts of a sweep directory.
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/output_files.hpp"
#include "sim/sweep/provenance.hpp"
#include "sim/sweep/sweep_bench.hpp"
#include "sim/sweep/sweep_plot.hpp"
#include "sim/sweep/sweep_report.hpp"
#include "sim/sweep/sweep_run.hpp"
#include "sim/sweep/sweep_slurm.hpp"
#include "sim/tfu/choices.hpp"
#include "sim/tfu/commands.hpp"
#include "sim/tfu/sampler_options.hpp"

namespace tfu::cli {
namespace {

namespace fs = std::filesystem;
using namespace tfu::sweep;

constexpr size_t kDefaultMaxTasks = 100;  // --slurm without --tasks: one task per point, at most this many

struct SweepOptions {
  std::string spec, out, collect;
  int workers = 0;
  bool plot = false, force = false, quiet = false, bench = false;
  bool slurm = false, slurm_dry_run = false;
  size_t tasks = 0;
  int cpus_per_task = 1;
  int run_task = -1;
  std::vector<std::string> sbatch_args;
};

// results.csv, columns.json, the plots and summary.md from the point files, all or nothing: each is
// written to a temporary (the plots drawn from results.csv's and columns.json's) and all are renamed
// into place together at the end, so a failed plot step leaves DIR as it was. CheckFailed when a
// point failed its golden compare or could not run.
void finish(const Spec& spec, const std::vector<Point>& points, const std::string& dir, bool plots) {
  const std::vector<nlohmann::json> files = read_point_files(dir, points);
  OutputFiles outputs(/*force=*/true);  // the sweep's own files in its own directory: replaced
  OutputFile& csv = outputs.add("results.csv", (fs::path(dir) / "results.csv").string());
  OutputFile& columns = outputs.add("columns.json", (fs::path(dir) / "columns.json").string());
  OutputFile& summary = outputs.add("summary.md", (fs::path(dir) / "summary.md").string());
  csv.stream() << results_csv(spec, points, files) << std::flush;  // flushed: the plot script reads it
  columns.stream() << columns_json(spec) << std::flush;
  const std::vector<Plot> charts =
      plots ? default_plots(spec, points, dir, outputs, csv.temp_path(), columns.temp_path()) : std::vector<Plot>{};
  summary.stream() << summary_markdown(spec, points, files, charts);
  outputs.commit();
  std::cout << fmt::format("tfu sweep: {} points -> {}/results.csv, summary.md{}\n", points.size(), dir,
                           charts.empty() ? "" : fmt::format(", {} plots", charts.size()));
  if (const size_t failed = failed_points(files); failed > 0)
    throw CheckFailed(fmt::format("{} of {} points failed the golden compare or could not run (results.csv: golden_equal, error)",
                                  failed, points.size()));
}

void run_slurm(const SweepOptions& o, const Spec& spec, const std::vector<Point>& points) {
  if (o.cpus_per_task < 1 || o.cpus_per_task > 1024) throw InputError("--cpus-per-task must be in 1..1024");
  SlurmJob job;
  job.tfu = self_executable();
  job.dir = fs::absolute(o.out).lexically_normal().string();
  job.tasks = o.tasks ? std::min(o.tasks, points.size()) : std::min(points.size(), kDefaultMaxTasks);
  job.cpus_per_task = o.cpus_per_task;
  job.sbatch_args = o.sbatch_args;
  const std::string script_path = (fs::path(job.dir) / "slurm" / "sweep.sbatch").string();
  const std::string script = batch_script(job);
  if (o.slurm_dry_run) {
    std::cout << script;
    std::string cmd;
    for (const std::string& a : sbatch_command(job, script_path)) cmd += (cmd.empty() ? "" : " ") + shell_quote(a);
    std::cout << fmt::format("# {} points in {} array tasks; would run: {}\n", points.size(), job.tasks, cmd);
    return;
  }
  // A submission that fails (no sbatch, sbatch refuses) leaves what it found (TFU-S E8): the directory
  // if this run created it, else the record and the script if this run wrote them, are removed.
  std::error_code ec;
  const fs::path dir(job.dir), record = dir / "sweep.json";
  const bool dir_existed = fs::exists(fs::symlink_status(dir, ec));
  const bool record_existed = fs::exists(fs::symlink_status(record, ec));
  const bool script_existed = fs::exists(fs::symlink_status(script_path, ec));
  std::string id;
  try {
    prepare_sweep_dir(o.out, spec, o.force);
    write_file_atomic(script_path, script, "--slurm batch script");
    fs::permissions(script_path, fs::perms::owner_exec, fs::perm_options::add);
    id = submit(job, script_path);
  } catch (...) {
    if (!dir_existed) {
      fs::remove_all(dir, ec);
    } else {
      if (!script_existed) fs::remove(script_path, ec);
      fs::remove(dir / "slurm", ec);  // only if empty
      if (!record_existed) {
        fs::remove(record, ec);
        fs::remove(dir / "points", ec);  // only if empty
      }
    }
    throw;
  }
  std::cout << fmt::format("tfu sweep: {} points in {} array tasks submitted as Slurm job {} (script {}); when it has "
                           "finished: tfu sweep --collect {}\n",
                           points.size(), job.tasks, id, script_path, job.dir);
}

void run(const SweepOptions& o) {
  if (!o.collect.empty()) {
    if (!o.spec.empty() || !o.out.empty()) throw InputError("--collect DIR takes no spec and no --out");
    const Spec spec = load_sweep_dir(o.collect);
    if (o.plot) (void)checked_plot_script();  // a missing plot step is found before anything is written
    finish(spec, expand(spec), o.collect, o.plot);
    return;
  }
  if (o.run_task >= 0) {  // one array task (the batch script's line)
    if (o.out.empty() || o.tasks == 0) throw InputError("--run-task needs --tasks and --out");
    if (static_cast<size_t>(o.run_task) >= o.tasks) throw InputError(fmt::format("--run-task {} must be below --tasks {}", o.run_task, o.tasks));
    const Spec spec = load_sweep_dir(o.out);
    const std::vector<Point> points = expand(spec);
    const RunSummary s = run_points(spec, points, o.out, {o.workers, static_cast<size_t>(o.run_task), o.tasks, !o.quiet});
    std::cout << fmt::format("tfu sweep: task {} of {}: {} points ({} ran, {} already done)\n", o.run_task, o.tasks, s.points,
                             s.ran, s.skipped);
    return;
  }
  if (o.spec.empty()) throw InputError("a sweep spec is needed (tfu sweep SPEC.json --out DIR), or --collect DIR");
  if (o.workers < 0 || o.workers > 1024) throw InputError("--workers must be in 0..1024 (0: every hardware thread)");
  const Spec spec = load_spec(o.spec);
  const std::vector<Point> points = expand(spec);  // every point validated before any runs
  if (o.bench) {
    std::cout << bench_report(bench(spec, points, o.workers));
    return;
  }
  if (o.out.empty()) throw InputError("--out DIR is needed");
  if (o.slurm || o.slurm_dry_run) {
    run_slurm(o, spec, points);
    return;
  }
  if (o.plot) (void)checked_plot_script();  // a missing plot step is found before anything runs
  prepare_sweep_dir(o.out, spec, o.force);
  const RunSummary s = run_points(spec, points, o.out, {o.workers, 0, 1, !o.quiet});
  // The run's line after finish (TFU-S E14: before it, a failed plot step's error was the second line);
  // a failed golden compare (exit 1) keeps it.
  const std::string ran = fmt::format("tfu sweep: {} points ran, {} already done, {:.1f} s", s.ran, s.skipped, s.wall_seconds);
  try {
    finish(spec, points, o.out, o.plot);
  } catch (const CheckFailed&) {
    print_summary_line(ran);
    throw;
  }
  print_summary_line(ran);
}

struct PlotOptions {
  std::string dir, x, y, series, series_note, kind = "line", out, title;
  std::vector<std::string> where;
  bool log_x = false, log_y = false, force = false;
};

void run_plot(const PlotOptions& o) {
  PlotRequest r;
  r.dir = o.dir;
  r.x = o.x;
  r.y = o.y;
  for (size_t p = 0; p < o.series.size();) {
    const size_t c = o.series.find(',', p);
    const std::string s = o.series.substr(p, c == std::string::npos ? std::string::npos : c - p);
    if (!s.empty()) r.series.push_back(s);
    if (c == std::string::npos) break;
    p = c + 1;
  }
  r.where = o.where;
  r.series_note = o.series_note;
  r.log_x = o.log_x;
  r.log_y = o.log_y;
  if (o.kind != "line" && o.kind != "bar") throw InputError(fmt::format("--kind '{}': expected line or bar", o.kind));
  r.kind = o.kind;
  r.title = o.title;
  OutputFiles outputs(o.force);  // the chart is renamed into place only when the script has drawn it
  plot(r, add_plot_output(outputs, "--out", o.out, o.force));
  outputs.commit();
  std::cout << o.out << '\n';
}

}  // namespace

void register_sweep(CLI::App& app) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* cmd = app.add_subcommand("sweep", "Design-space sweep: unit configurations x scenes x filters, golden compare, "
                                              "results.csv, summary.md, plots; local or Slurm (docs/design-space.md)");
  add_plain_option(*cmd);
  cmd->add_option("spec", o->spec, "Sweep spec JSON (docs/design-space.md)");
  cmd->add_option("--out", o->out, "Sweep directory: points/, results.csv, summary.md (resumable: complete points are skipped)");
  cmd->add_option("--workers", o->workers, "Points run at once on the local runner (0: every hardware thread)")->capture_default_str();
  cmd->add_flag("--plot", o->plot, "Also draw the summary's charts (DIR/plot_*.png; needs /usr/bin/python3 with matplotlib)");
  cmd->add_flag("--force", o->force, "Use an --out directory that is not empty and holds no sweep");
  cmd->add_flag("--quiet", o->quiet, "No progress display");
  cmd->add_flag("--bench", o->bench, "Measure the local runner: the single runs' sum against the sweep's wall time, and the "
                                     "per-point overhead (writes nothing)");
  cmd->add_flag("--slurm", o->slurm, "Submit the points as one Slurm job array (DIR must be on a shared file system)");
  cmd->add_flag("--slurm-dry-run", o->slurm_dry_run, "Print the batch script and the sbatch command; submit nothing");
  cmd->add_option("--tasks", o->tasks, "Slurm array tasks (default: one per point, at most 100)")->check(unsigned_integer());
  cmd->add_option("--cpus-per-task", o->cpus_per_task, "CPUs (worker threads) per array task")->capture_default_str();
  cmd->add_option("--sbatch-arg", o->sbatch_args, "An extra sbatch option, e.g. --sbatch-arg=--partition=big (repeatable)");
  cmd->add_option("--collect", o->collect, "Check that every point of the sweep in DIR has its result; write results.csv, summary.md");
  cmd->add_option("--run-task", o->run_task, "Run one array task's share of DIR's points (the batch script's line)");
  cmd->callback([o] { run(*o); });

  auto p = std::make_shared<PlotOptions>();
  CLI::App* pc = app.add_subcommand("plot", "Chart of a sweep's results.csv (PNG; scripts/plot, matplotlib)");
  pc->add_option("dir", p->dir, "Sweep directory (results.csv, columns.json)")->required();
  pc->add_option("--x", p->x, "Column on the x axis (e.g. cache.capacity_bytes)")->required();
  pc->add_option("--y", p->y, "Column on the y axis (e.g. bytes_per_pixel)")->required();
  pc->add_option("--series", p->series, "Column(s), comma-separated, whose values make the lines (e.g. filter)");
  pc->add_option("--where", p->where, "Only rows with COLUMN=VALUE (repeatable)");
  pc->add_option("--series-note", p->series_note, "A column whose value each legend entry shows (e.g. filter_gates)");
  pc->add_flag("--log-x", p->log_x, "Logarithmic x axis (base 2 over powers of two)");
  pc->add_flag("--log-y", p->log_y, "Logarithmic y axis");
  pc->add_option("--kind", p->kind, "line or bar")->capture_default_str();
  pc->add_option("--title", p->title, "Chart title");
  pc->add_option("--out", p->out, "Output PNG")->required();
  pc->add_flag("--force", p->force, "Overwrite --out");
  pc->callback([p] { run_plot(*p); });
}

}  // namespace tfu::cli
