// Grid convergence of a swimming scene (issue 33, docs/convergence.md): the same scene, tank and
// stroke on a sequence of grids, the markers following each grid, and the swimming figures'
// observed order, Richardson extrapolate and Roache's GCI (studies/grid_convergence.hpp).
// Works for a jellyfish (planar or axisymmetric water), for a generated IB2d structure and for the
// 3D scene's shell bell (tank.geometry = "3d": grids NXxNYxNZ; docs/three-d.md).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>

#include "jellysim/core/errors.hpp"
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/experiments/jellyfish_runs.hpp"
#include "jellysim/render/plot.hpp"
#include "jellysim/scene/jellyfish_3d_scene.hpp"
#include "jellysim/studies/grid_convergence.hpp"
#include "jellyfish_3d.hpp"

namespace jellysim::experiments {
namespace {

using config::format_number;

struct Grid {
  int nx = 0, ny = 0, nz = 0;  ///< nz: 0 in planar or axisymmetric water
};

/// One "NXxNY" or "NXxNYxNZ" item.
Grid parse_grid(const std::string& item, int axes, const std::string& what) {
  const std::string form = axes == 3 ? "NXxNYxNZ (e.g. 32x48x32)" : "NXxNY (e.g. 96x128)";
  std::array<int, 3> n{};
  const char* p = item.data();
  const char* last = item.data() + item.size();
  for (int d = 0; d < axes; ++d) {
    auto [end, ec] = std::from_chars(p, last, n[static_cast<std::size_t>(d)]);
    const bool separator_next = d + 1 < axes;
    if (ec != std::errc() || (separator_next && (end == last || (*end != 'x' && *end != 'X'))) ||
        (!separator_next && end != last))
      throw InputError(what + ": '" + item + "' is not " + form);
    if (n[static_cast<std::size_t>(d)] < 4 || n[static_cast<std::size_t>(d)] > 4096)
      throw InputError(what + ": '" + item + "' has cells outside [4, 4096]");
    p = end + 1;
  }
  return {n[0], n[1], axes == 3 ? n[2] : 0};
}

/// "96x128,192x256" (or NXxNYxNZ items for the 3D scene, `axes` 3): cells of each grid, coarsest
/// first, each finer than the one before.
std::vector<Grid> parse_grids(const std::string& list, int axes) {
  const std::string what = "field 'grids' = \"" + list.substr(0, 80) + "\"";
  std::vector<Grid> grids;
  for (std::size_t at = 0; at <= list.size();) {
    const std::size_t end = std::min(list.find(',', at), list.size());
    const Grid g = parse_grid(list.substr(at, end - at), axes, what);
    if (!grids.empty() && !(g.nx > grids.back().nx && g.ny > grids.back().ny && (axes < 3 || g.nz > grids.back().nz)))
      throw InputError(what + ": each grid must have more cells along every axis than the one before (coarsest first)");
    grids.push_back(g);
    at = end + 1;
  }
  if (grids.size() < 2 || grids.size() > 8) throw InputError(what + ": give 2 to 8 grids (3 for an order and a GCI)");
  return grids;
}

std::string grid_name(const Grid& g) {
  return std::to_string(g.nx) + "x" + std::to_string(g.ny) + (g.nz > 0 ? "x" + std::to_string(g.nz) : "");
}

/// What the runs swim: the first jellyfish, a single generated IB2d structure, or the 3D shell bell.
enum class Swimmer { jellyfish, structure, shell_3d };

struct Study {
  std::vector<Grid> grids;
  std::vector<jellyfish::SwimSettings> runs;  ///< one per grid (planar or axisymmetric water)
  std::vector<scene::Swim3dSettings> runs_3d;  ///< one per grid (the 3D scene)
  Swimmer swimmer = Swimmer::jellyfish;
  int cycles = 5;
  int frames_per_cycle = 24;
  double period_s = 0.0;
  double bell_width_m = 0.0;  ///< the bell's diameter (a structure: the width of its non-target vertices)
};

/// The structure's width across x without its target points (IB2d's flow blocker).
double structure_width(const jellyfish::Ib2dObjectSpec& s) {
  std::vector<char> target(s.structure.vertices.size(), 0);
  for (const auto& t : s.structure.targets) target[static_cast<std::size_t>(t.point)] = 1;
  double lo = INFINITY, hi = -INFINITY;
  for (std::size_t v = 0; v < s.structure.vertices.size(); ++v)
    if (!target[v]) lo = std::min(lo, s.structure.vertices[v].x), hi = std::max(hi, s.structure.vertices[v].x);
  return hi > lo ? hi - lo : 0.0;
}

/// Refuses scenes whose markers would not follow the grid.
void refuse_fixed_spacing(const config::Config& c) {
  if (c.number("jellyfish.spacing") > 0)
    throw InputError("field 'jellyfish.spacing' = " + format_number(c.number("jellyfish.spacing")) +
                     ": the convergence study lets the markers follow the grid (Peskin's rule); set it to 0");
  for (std::size_t k = 0; k < c.array_size("objects"); ++k)
    if (c.element("objects", k).has("files"))
      throw InputError("objects[" + std::to_string(k) + "]: an IB2d structure read from files has the spacing of its "
                       "files, which a finer grid cannot change; use model = \"hoover-miller\" (generated at each grid)");
}

/// Which swimmer the scene has and its stroke period.
void read_swimmer(const jellyfish::SwimSettings& s, Study& study) {
  if (!s.school.empty()) {
    study.swimmer = Swimmer::jellyfish;
    study.period_s = 1.0 / s.jellyfish().frequency_hz;
    study.bell_width_m = s.jellyfish().diameter_m;
    return;
  }
  if (s.structures.size() != 1 || s.structures[0].schedules.empty() || !(s.structures[0].schedules[0].frequency_hz > 0))
    throw InputError("experiment convergence needs a jellyfish, or exactly one IB2d structure (type = \"ib2d\", model = "
                     "\"hoover-miller\") whose first schedule has a frequency: the stroke's period");
  study.swimmer = Swimmer::structure;
  study.period_s = 1.0 / s.structures[0].schedules[0].frequency_hz;
  study.bell_width_m = structure_width(s.structures[0]);
}

/// The 3D scene on each grid: the shell's edges follow the grid (jellyfish.shell_edge = 0: half a
/// cell), frames_per_cycle frames a cycle.
void read_study_3d(const config::Config& config, Study& study) {
  if (config.number("jellyfish.shell_edge") > 0)
    throw InputError("field 'jellyfish.shell_edge' = " + format_number(config.number("jellyfish.shell_edge")) +
                     ": the convergence study lets the shell's edges follow the grid (half a cell); set it to 0");
  study.swimmer = Swimmer::shell_3d;
  for (const Grid& g : study.grids) {
    config::Config c = config;
    c.set("tank.cells=[" + std::to_string(g.nx) + ", " + std::to_string(g.ny) + ", " + std::to_string(g.nz) + "]");
    c.set("output.frames_per_cycle=" + std::to_string(study.frames_per_cycle));
    if (study.runs_3d.empty()) {
      const scene::Swim3dSettings first = scene::read_swim3d_settings(c);
      study.period_s = 1.0 / first.spec.bell.slice.frequency_hz;
      study.bell_width_m = first.spec.bell.slice.diameter_m;
    }
    c.set("duration=" + io::format_double(study.cycles * study.period_s));
    study.runs_3d.push_back(scene::read_swim3d_settings(c));
  }
}

Study read_study(const config::Config& config) {
  Study study;
  const bool three_d = scene::is_3d_scene(config);
  study.grids = parse_grids(config.string("grids"), three_d ? 3 : 2);
  study.cycles = static_cast<int>(config.integer("cycles", 2, 100));
  study.frames_per_cycle = static_cast<int>(config.integer("frames_per_cycle", 4, 1000));
  if (three_d) {
    read_study_3d(config, study);
    return study;
  }
  refuse_fixed_spacing(config);
  for (const Grid& g : study.grids) {
    config::Config c = config;
    c.set("tank.cells=[" + std::to_string(g.nx) + ", " + std::to_string(g.ny) + "]");
    if (study.runs.empty()) read_swimmer(scene::read_swim_settings(c), study);
    // Cycles' ends are frames: the frame interval divides the period.
    c.set("duration=" + io::format_double(study.cycles * study.period_s));
    c.set("output.frame_interval=" + io::format_double(study.period_s / study.frames_per_cycle));
    study.runs.push_back(scene::read_swim_settings(c));
  }
  return study;
}

/// One grid's figures (convergence.csv's row).
struct Row {
  Grid grid;
  double cells_across_bell = 0.0, markers = 0.0;
  double first_cycle_m = 0.0, distance_per_cycle_m = 0.0;
  double min_volume_ratio = NAN, peak_speed_m_per_s = 0.0;
  double steps = 0.0, wall_seconds = 0.0;
  std::vector<double> cycle_m;  ///< displacement over each cycle
};

/// The swimmer's position along its axis (a structure: its centroid's y) at each recorded frame,
/// and its markers (a structure's: its vertices but the targets).
std::vector<double> positions(const Study& study, const jellyfish::SwimSettings& s, const SwimRecording& rec,
                              double& markers) {
  std::vector<double> p;
  if (study.swimmer == Swimmer::jellyfish) {
    if (rec.frames.empty()) return p;  // a run that failed before its first frame
    for (const auto& m : rec.metrics) p.push_back(m.position);
    const jellyfish::SliceFrame& f = rec.frames.front();
    markers = static_cast<double>(f.umbrella.size());
    for (const auto& strand : f.tentacles) markers += static_cast<double>(strand.size()) - 1.0;  // roots are umbrella points
    return p;
  }
  const elastic::Ib2dStructure& st = s.structures.front().structure;
  markers = static_cast<double>(st.vertices.size() - st.targets.size());
  for (const auto& c : rec.structure_centroids) p.push_back(c.front().y - rec.structure_centroids.front().front().y);
  return p;
}

Row run_grid(const Study& study, std::size_t k, const sim::ProgressCallback& progress, std::string& failure) {
  const jellyfish::SwimSettings& s = study.runs[k];
  Row row;
  row.grid = study.grids[k];
  row.cells_across_bell = study.bell_width_m / (s.tank.width_m / s.tank.cells_x);
  const SwimRecording rec = run_swim(s, {}, nullptr, progress);
  failure = rec.stats.failure;
  row.steps = static_cast<double>(rec.stats.steps);
  row.wall_seconds = rec.stats.wall_seconds;
  const std::vector<double> p = positions(study, s, rec, row.markers);
  for (int c = 1; c <= study.cycles; ++c) {
    const auto end = static_cast<std::size_t>(c * study.frames_per_cycle);
    if (end >= p.size()) break;
    row.cycle_m.push_back(p[end] - p[end - static_cast<std::size_t>(study.frames_per_cycle)]);
  }
  if (!row.cycle_m.empty()) row.first_cycle_m = row.cycle_m.front();
  double later = 0.0;
  for (std::size_t c = 1; c < row.cycle_m.size(); ++c) later += row.cycle_m[c];
  row.distance_per_cycle_m = row.cycle_m.size() > 1 ? later / static_cast<double>(row.cycle_m.size() - 1) : NAN;
  const double dt = s.frame_interval_s;
  for (std::size_t f = 1; f < p.size(); ++f) row.peak_speed_m_per_s = std::max(row.peak_speed_m_per_s, std::abs(p[f] - p[f - 1]) / dt);
  if (study.swimmer == Swimmer::jellyfish && !rec.metrics.empty()) {
    row.min_volume_ratio = INFINITY;
    for (const auto& m : rec.metrics) row.min_volume_ratio = std::min(row.min_volume_ratio, m.volume_ratio);
  }
  return row;
}

/// The 3D scene's run on grid k: the bell's surface centroid along its first axis at each frame.
Row run_grid_3d(const Study& study, std::size_t k, const io::OutputDir& out, const sim::ProgressCallback& progress,
                std::string& failure) {
  const scene::Swim3dSettings& s = study.runs_3d[k];
  Row row;
  row.grid = study.grids[k];
  row.cells_across_bell = study.bell_width_m / (s.spec.tank_size_m[0] / s.spec.cells[0]);
  const Recording3d rec = run_3d(s, out, progress);
  failure = rec.failure;
  row.markers = static_cast<double>(rec.markers);
  row.steps = static_cast<double>(rec.timings.steps);
  row.wall_seconds = rec.wall_seconds;
  row.cycle_m = swim3d::summarize(rec.frames, study.frames_per_cycle).cycle_distance_m;
  if (!row.cycle_m.empty()) row.first_cycle_m = row.cycle_m.front();
  double later = 0.0;
  for (std::size_t c = 1; c < row.cycle_m.size(); ++c) later += row.cycle_m[c];
  row.distance_per_cycle_m = row.cycle_m.size() > 1 ? later / static_cast<double>(row.cycle_m.size() - 1) : NAN;
  if (rec.frames.empty()) return row;
  const swim3d::Frame3d& first = rec.frames.front();
  const auto along = [&](const swim3d::Frame3d& f) {
    double d = 0.0;
    for (std::size_t c = 0; c < 3; ++c) d += (f.centroid[c] - first.centroid[c]) * first.axis[c];
    return d;
  };
  const double dt = study.period_s / study.frames_per_cycle;
  row.min_volume_ratio = INFINITY;
  for (std::size_t f = 0; f < rec.frames.size(); ++f) {
    row.min_volume_ratio = std::min(row.min_volume_ratio, rec.frames[f].cavity_volume_m3 / first.cavity_volume_m3);
    if (f == 0) continue;
    const double speed = std::abs(along(rec.frames[f]) - along(rec.frames[f - 1])) / dt;
    row.peak_speed_m_per_s = std::max(row.peak_speed_m_per_s, speed);
  }
  return row;
}

std::string cell(double v) { return std::isfinite(v) ? io::format_double(v) : std::string(); }

/// convergence.csv; the 3D scene's grids add cells_z (after the 2D columns, which keep their order).
io::CsvWriter table(const std::vector<Row>& rows, bool three_d) {
  std::vector<std::string> columns{"cells_x", "cells_y", "cells_across_bell", "markers", "first_cycle_m",
                                   "distance_per_cycle_m", "min_volume_ratio", "peak_speed_m_per_s", "steps",
                                   "wall_seconds"};
  if (three_d) columns.push_back("cells_z");
  io::CsvWriter csv(columns);
  for (const Row& r : rows) {
    std::vector<std::string> values{std::to_string(r.grid.nx), std::to_string(r.grid.ny), cell(r.cells_across_bell),
                                    cell(r.markers), cell(r.first_cycle_m), cell(r.distance_per_cycle_m),
                                    cell(r.min_volume_ratio), cell(r.peak_speed_m_per_s), cell(r.steps),
                                    cell(r.wall_seconds)};
    if (three_d) values.push_back(std::to_string(r.grid.nz));
    csv.text_row(values);
  }
  return csv;
}

/// A figure of every grid: name, unit, getter.
struct Figure {
  const char* name;
  const char* label;
  const char* unit;
  double Row::*value;
};
constexpr Figure kFigures[] = {{"distance_per_cycle_m", "distance per cycle", "m", &Row::distance_per_cycle_m},
                               {"first_cycle_m", "first cycle", "m", &Row::first_cycle_m},
                               {"min_volume_ratio", "smallest volume ratio", "", &Row::min_volume_ratio},
                               {"peak_speed_m_per_s", "peak speed", "m/s", &Row::peak_speed_m_per_s}};

studies::GridConvergence analyse(const std::vector<Row>& rows, double Row::*value, const Study& study) {
  std::vector<double> h, f;
  for (const Row& r : rows) {
    if (!std::isfinite(r.*value)) return {};
    h.push_back(study.bell_width_m / r.cells_across_bell);
    f.push_back(r.*value);
  }
  return studies::grid_convergence(h, f);
}

nlohmann::ordered_json describe(const studies::GridConvergence& g) {
  auto opt = [](const std::optional<double>& v) { return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(); };
  return {{"observed_order", opt(g.observed_order)}, {"extrapolated", opt(g.extrapolated)},
          {"gci_fine", opt(g.gci_fine)}, {"relative_change_finest", opt(g.relative_change_finest)},
          {"oscillatory", g.oscillatory}};
}

/// "0.0342": three significant digits for a legend.
std::string short_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

/// convergence.png: every figure over its extrapolate (or its finest value) against the cell width
/// in bell widths, 1 / (cells across the bell): Richardson's limit is the value at 0, the dashed 1.
void write_figure_chart(const io::OutputDir& out, const std::vector<Row>& rows, const Study& study) {
  render::ChartSpec chart;
  chart.title = "Grid convergence: each figure over its extrapolated value";
  chart.x_label = "1 / cells across the bell";
  chart.y_label = "figure / extrapolated";
  std::vector<double> x;
  for (const Row& r : rows) x.push_back(1.0 / r.cells_across_bell);
  for (const Figure& fig : kFigures) {
    const studies::GridConvergence g = analyse(rows, fig.value, study);
    const double last = rows.back().*(fig.value);
    if (!std::isfinite(last) || last == 0) continue;
    const double reference = g.extrapolated && *g.extrapolated != 0 ? *g.extrapolated : last;
    render::Series s;
    s.label = std::string(fig.label) + (g.extrapolated ? ": extrapolated " : ": finest grid ") + short_number(reference) +
              " " + fig.unit;
    s.markers = true;
    s.x = x;
    for (const Row& r : rows) s.y.push_back(r.*(fig.value) / reference);
    chart.series.push_back(s);
  }
  render::Series one;
  one.label = "grid-independent (Richardson)";
  one.dashed = true;
  one.x = {0.0, x.front()};
  one.y = {1.0, 1.0};
  chart.series.push_back(one);
  out.write_text("convergence.png", render::chart_png(chart));
}

nlohmann::ordered_json figures(const std::vector<Row>& rows, const Study& study) {
  const studies::GridConvergence d = analyse(rows, &Row::distance_per_cycle_m, study);
  auto opt = [](const std::optional<double>& v) { return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(); };
  nlohmann::ordered_json fig;
  fig["units"] = {{"length", "m"}, {"speed", "m/s"}, {"time", "s"}};
  fig["swimmer"] = study.swimmer == Swimmer::jellyfish   ? "jellyfish"
                   : study.swimmer == Swimmer::structure ? "ib2d structure"
                                                         : "3d shell bell";
  fig["cycles"] = study.cycles;
  fig["bell_width_m"] = study.bell_width_m;
  fig["observed_order"] = opt(d.observed_order);
  fig["extrapolated_distance_per_cycle_m"] = opt(d.extrapolated);
  fig["extrapolated_distance_per_cycle_bell_diameters"] =
      d.extrapolated ? nlohmann::ordered_json(*d.extrapolated / study.bell_width_m) : nlohmann::ordered_json();
  fig["gci_fine"] = opt(d.gci_fine);
  fig["relative_change_finest"] = opt(d.relative_change_finest);
  fig["oscillatory"] = d.oscillatory;
  nlohmann::ordered_json each;
  for (const Figure& f : kFigures) each[f.name] = describe(analyse(rows, f.value, study));
  fig["figures"] = each;
  nlohmann::ordered_json grids = nlohmann::ordered_json::array();
  for (const Row& r : rows) {
    nlohmann::ordered_json cells = {r.grid.nx, r.grid.ny};
    if (r.grid.nz > 0) cells.push_back(r.grid.nz);
    grids.push_back({{"cells", cells}, {"cycle_displacements_m", r.cycle_m}, {"wall_seconds", r.wall_seconds}});
  }
  fig["grids"] = grids;
  return fig;
}

std::function<Outcome(const io::OutputDir&)> prepare_convergence(const Context& ctx) {
  const Study study = read_study(ctx.config);
  return [study, ctx](const io::OutputDir& out) {
    std::vector<Row> rows;
    std::string failure;
    for (std::size_t k = 0; k < study.grids.size() && failure.empty(); ++k) {
      std::string why;
      const bool three_d = study.swimmer == Swimmer::shell_3d;
      rows.push_back(three_d ? run_grid_3d(study, k, out, ctx.progress, why) : run_grid(study, k, ctx.progress, why));
      if (!why.empty()) failure = "grid " + grid_name(study.grids[k]) + ": " + why;
      out.write_text("convergence.csv", table(rows, three_d).text());  // each grid as it finishes
    }
    std::vector<Row> whole = rows;  // the grids whose runs completed
    if (!failure.empty()) whole.pop_back();
    if (whole.size() >= 2) write_figure_chart(out, whole, study);
    write_summary(out, "experiment convergence", ctx.config, figures(whole, study), failure);
    return Outcome{failure};
  };
}

}  // namespace

Experiment convergence_experiment() {
  Experiment e{"convergence",
               "Grid convergence of a swimming scene (planar, axisymmetric or 3D water): each grid's distance per cycle, "
               "first cycle, volume ratio and peak speed; observed order, Richardson extrapolate, Roache's GCI "
               "(convergence.csv, convergence.png)",
               "experiments/convergence.toml", prepare_convergence};
  e.base_path = "scenes/jellyfish.toml";
  e.shorthands = {"grids", "cycles"};
  return e;
}

}  // namespace jellysim::experiments
