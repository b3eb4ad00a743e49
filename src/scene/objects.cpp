#include "jellysim/scene/objects.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "jellysim/core/errors.hpp"
#include "jellysim/io/ib2d_files.hpp"
#include "jellysim/io/output.hpp"
#include "jellysim/jellyfish/hoover_miller.hpp"

namespace jellysim::scene {
namespace {

using config::Range;
constexpr double kDegree = std::numbers::pi / 180.0;
const Range kStiffness{0.0, 1e9, true, false};  ///< N/m of an obstacle's tethers (issue 23: an upper bound)

/// A field of an object; `value` is its default as TOML ("" when it has none: required or unset).
Parameter field(std::string key, Type type, std::string value, std::string unit, Range range, std::string description,
                std::vector<std::string> choices = {}, int length = 0) {
  return {std::move(key), type, std::move(value), std::move(unit), range, std::move(choices), length,
          std::move(description)};
}

Parameter type_field(const std::string& type) {
  return field("type", Type::choice, "\"" + type + "\"", "", {}, "the object type (required)", object_types());
}

/// The jellyfish object: every [jellyfish] field of the scene may be given and overrides the scene's.
ParameterTable make_jellyfish_object() {
  return ParameterTable("jellyfish object", "", {type_field("jellyfish")}, "none");
}

/// A rigid obstacle of `shape`: the shape's own fields, then the tethers and the prescribed path
/// every obstacle has (p(t) = p0 + v t + a sin 2πft).
ParameterTable make_obstacle(const std::string& shape, std::vector<Parameter> own) {
  std::vector<Parameter> p{type_field(shape)};
  for (Parameter& f : own) p.push_back(std::move(f));
  const std::vector<Parameter> common{
      field("tether_stiffness", Type::number, "40000.0", "N/m²", kStiffness,
            "the tethers holding the outline, per metre of outline and of depth (the same obstacle at any marker "
            "spacing)"),
      field("stiffness", Type::number, "", "N/m", kStiffness,
            "instead of tether_stiffness: per marker and metre of depth (IB2d's way); not both"),
      field("velocity", Type::vec2, "[0.0, 0.0]", "m/s", {}, "v: steady drift"),
      field("amplitude", Type::vec2, "[0.0, 0.0]", "m", {}, "a: oscillation amplitude"),
      field("frequency", Type::number, "0.0", "Hz", Range::non_negative(), "f: oscillation frequency"),
  };
  p.insert(p.end(), common.begin(), common.end());
  return ParameterTable(shape + " obstacle", "", std::move(p), "none");
}

ParameterTable make_ib2d_object() {
  std::vector<Parameter> p{
      type_field("ib2d"),
      field("files", Type::text, "", "",  {},
            "IB2d's files \"path/stem\" (.vertex, .spring, .d_spring, .beam, .nonInv_beam, .target; relative to "
            "the working directory); exactly one of files and model"),
      field("model", Type::choice, "", "", {},
            "a generated model: IB2d's Hoover-Miller bell, or its variant with muscles per unit length",
            {"hoover-miller", "hoover-miller-consistent"}),
      field("resolution", Type::integer, "", "", Range::closed(16, 4096),
            "with model: IB2d's N, a multiple of 8; by default 8 m / the tank's mesh width"),
      field("offset", Type::vec2, "[0.0, 0.0]", "m", {}, "added to every vertex"),
      field("schedules", Type::tables, "[]", "", {},
            "[[objects.schedules]]: springs whose rest length or stiffness follow a law of t (below)"),
  };
  return ParameterTable("ib2d object", "", std::move(p), "none");
}

ParameterTable make_schedule() {
  std::vector<Parameter> p{
      field("springs", Type::integers, "", "", Range::closed(1, 100'000'000),
            "required: [first, last], first <= last, rows of the .spring file from 1; or \"muscles\", a generated "
            "model's muscle springs",
            {}, 2),
      field("column", Type::choice, "\"rest_length\"", "", {}, "the column the law sets (stiffness in IB2d's units)",
            {"rest_length", "stiffness"}),
      field("law", Type::choice, "\"abs-cos\"", "", {}, "the law of t (docs/ib2d.md)",
            {"constant", "abs-cos", "sine", "stroke"}),
      field("frequency", Type::number, "1.0", "Hz", Range::closed(0.0, 1000.0), "cycles per second"),
      field("amplitude", Type::number, "1.0", "", Range::closed(-1e12, 1e12), "the law's amplitude (the column's unit)"),
      field("mean", Type::number, "0.0", "", Range::closed(0.0, 1e12), "sine only: the mean value"),
      field("gamma", Type::number, "0.5", "", Range{0.0, 1.0, true, false}, "stroke only: the contracted fraction"),
  };
  return ParameterTable("ib2d schedule", "", std::move(p), "none");
}

/// Fails on fields an object of this type does not have: the table lists them all.
void require_known_fields(const config::Config& o, const ParameterTable& table, const std::string& where) {
  for (const std::string& k : o.keys())
    if (!table.find(k)) {
      std::string list;
      for (const Parameter& a : table.parameters()) list += (list.empty() ? "" : ", ") + a.key;
      throw InputError(where + ": unknown field '" + k + "' (allowed: " + list + ")");
    }
}

/// Limits of a polygon file: a few MiB of text and 10,000 vertices are far beyond any obstacle
/// outline (the markers resample it at half a cell); the polygon checks sort and sweep
/// (jellyfish/segment_sweep.hpp: a 50,000-vertex outline in milliseconds).
constexpr std::uintmax_t kMaxPolygonFileBytes = 4u << 20;
constexpr std::size_t kMaxPolygonVertices = 10000;

/// One number filling the whole token (strict: "O.6" or "1.2.3" are not numbers).
std::optional<double> parse_number(std::string_view token) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (ec != std::errc() || end != token.data() + token.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

/// Polygon vertices from a text file: one "x y" or "x,y" pair (metres) per line; '#' starts a
/// comment; blank lines are skipped. Anything else is an error naming the line: a regular file
/// only (not a directory or a device such as /dev/zero), at most kMaxPolygonFileBytes.
std::vector<Vec2> read_polygon_file(const std::string& path, const std::string& where) {
  const std::string file = where + ": polygon file '" + path + "'";
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status))
    throw InputError(file + " cannot be read: " + (ec ? ec.message() : "no such file"));
  if (!std::filesystem::is_regular_file(status))
    throw InputError(file + " is not a regular file (a directory or a device)");
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (ec || bytes > kMaxPolygonFileBytes)
    throw InputError(file + " is " + std::to_string(bytes) + " bytes; at most " + std::to_string(kMaxPolygonFileBytes));
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(file + " cannot be read: " + io::os_reason(errno ? errno : EACCES));
  std::vector<Vec2> points;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::replace(line.begin(), line.end(), ',', ' ');
    std::vector<std::string_view> tokens;
    for (std::size_t at = line.find_first_not_of(" \t\r"); at != std::string::npos;) {
      const std::size_t end = std::min(line.find_first_of(" \t\r", at), line.size());
      tokens.push_back(std::string_view(line).substr(at, end - at));
      at = line.find_first_not_of(" \t\r", end);
    }
    if (tokens.empty()) continue;  // blank or comment line
    const auto x = parse_number(tokens[0]);
    const auto y = tokens.size() > 1 ? parse_number(tokens[1]) : std::nullopt;
    if (tokens.size() != 2 || !x || !y)
      throw InputError(file + " line " + std::to_string(number) + ": expected two numbers \"x y\", got \"" +
                       line.substr(0, 60) + "\"");
    if (points.size() == kMaxPolygonVertices)
      throw InputError(file + " has more than " + std::to_string(kMaxPolygonVertices) + " vertices");
    points.push_back({*x, *y});
  }
  return points;
}

/// The polygon's vertices: exactly one of `points` = [x0, y0, x1, y1, ...] or `file`.
std::vector<Vec2> read_polygon(const Reader& r, const std::string& where) {
  const config::Config& o = r.config();
  if (o.has("points") == o.has("file"))
    throw InputError(where + ": a polygon needs exactly one of 'points' = [x0, y0, x1, y1, ...] or 'file'");
  if (o.has("file")) return read_polygon_file(r.text("file"), where);
  const std::vector<double> xy = r.numbers("points");
  if (xy.size() % 2 != 0) throw InputError(where + ": field 'points' needs an even count [x0, y0, x1, y1, ...]");
  std::vector<Vec2> vertices;
  for (std::size_t k = 0; k + 1 < xy.size(); k += 2) vertices.push_back({xy[k], xy[k + 1]});
  return vertices;
}

/// The shape's own fields of an obstacle (centre, radius, size, angle_deg; a polygon's vertices).
void read_shape(const Reader& r, const std::string& where, jellyfish::ObstacleSpec& spec) {
  const config::Config& o = r.config();
  auto required = [&](const char* key) {
    if (!o.has(key)) throw InputError(where + ": missing field '" + key + "'");
  };
  if (spec.shape != jellyfish::ObstacleShape::polygon) {
    required("centre");
    spec.centre_m = r.vec2("centre");
  }
  if (spec.shape == jellyfish::ObstacleShape::circle) {
    required("radius");
    spec.radius_m = r.number("radius");
  }
  if (spec.shape == jellyfish::ObstacleShape::box) {
    required("size");
    spec.size_m = r.vec2("size");
    if (o.has("angle_deg")) spec.angle_rad = r.number("angle_deg") * kDegree;
  }
  if (spec.shape == jellyfish::ObstacleShape::polygon) spec.vertices_m = read_polygon(r, where);
}

/// One [[objects.schedules]] table of an IB2d object: a column of a run of its springs as a law of t.
/// `muscles`: the rows of a generated model's muscle springs (empty when the object has none).
jellyfish::SpringSchedule read_schedule(const config::Config& o, const std::string& where,
                                        std::optional<std::array<int, 2>> muscles) {
  const Reader r(o, object_parameters("schedules"));
  require_known_fields(o, r.table(), where);
  if (!o.has("springs")) throw InputError(where + ": missing field 'springs' = [first, last] (rows of the .spring file, from 1)");
  jellyfish::SpringSchedule s;
  if (muscles && o.literal("springs") == "\"muscles\"") {
    s.first = (*muscles)[0];
    s.last = (*muscles)[1];
  } else {
    const std::vector<std::int64_t> rows = r.integers("springs");
    if (rows[1] < rows[0])
      throw InputError(where + ": field 'springs' must be [first, last] with first <= last (rows of the .spring file, "
                               "from 1)" + (muscles ? std::string(", or \"muscles\"") : std::string()));
    s.first = static_cast<int>(rows[0] - 1);
    s.last = static_cast<int>(rows[1] - 1);
  }
  if (o.has("column")) s.stiffness = r.choice("column") == "stiffness";
  if (o.has("law")) s.law = *jellyfish::schedule_law_from_string(r.choice("law"));
  if (o.has("frequency")) s.frequency_hz = r.number("frequency");
  if (o.has("amplitude")) s.amplitude = r.number("amplitude");
  if (o.has("mean")) s.mean = r.number("mean");
  if (o.has("gamma")) s.gamma = r.number("gamma");
  return s;
}

/// The Hoover-Miller bell at `resolution` (IB2d's N; by default the tank's, mesh width 8/N m).
jellyfish::HooverMillerBell generated_model(const Reader& r, const std::string& where, const coupling::TankSpec& tank) {
  jellyfish::HooverMillerSpec hm;
  hm.muscles_per_length = r.choice("model") == "hoover-miller-consistent";
  if (r.config().has("resolution")) {
    hm.resolution = static_cast<int>(r.integer("resolution"));
  } else {
    const double n = std::round(8.0 * tank.cells_y / tank.height_m);
    if (!(n >= 16 && n <= 4096))
      throw InputError(where + ": the tank's mesh width " + config::format_number(tank.height_m / tank.cells_y) +
                       " m gives IB2d's N = 8 m / mesh width = " + config::format_number(n) +
                       ", outside [16, 4096]; set 'resolution'");
    hm.resolution = static_cast<int>(n);
  }
  if (hm.resolution % 8 != 0)
    throw InputError(where + ": field 'resolution' = " + std::to_string(hm.resolution) + " must be a multiple of 8");
  return jellyfish::hoover_miller_bell(hm);
}

/// A spec's own check (std::invalid_argument) as an input error.
template <typename Spec>
void validate_input(const Spec& spec) {
  try {
    jellyfish::validate(spec);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
}

}  // namespace

const std::vector<std::string>& object_types() {
  static const std::vector<std::string> types{"jellyfish", "circle", "box", "polygon", "ib2d"};
  return types;
}

const ParameterTable& object_parameters(const std::string& type) {
  static const std::map<std::string, ParameterTable> tables = [] {
    std::map<std::string, ParameterTable> t;
    t.emplace("jellyfish", make_jellyfish_object());
    t.emplace("circle", make_obstacle("circle", {
        field("centre", Type::vec2, "", "m", {}, "required"),
        field("radius", Type::number, "", "m", Range::positive(), "required")}));
    t.emplace("box", make_obstacle("box", {
        field("centre", Type::vec2, "", "m", {}, "required"),
        field("size", Type::vec2, "", "m", {}, "required: width and height"),
        field("angle_deg", Type::number, "0.0", "°", Range::closed(-360, 360), "rotation, counter-clockwise")}));
    t.emplace("polygon", make_obstacle("polygon", {
        field("points", Type::numbers, "", "m", {}, "[x0, y0, x1, y1, ...], either orientation; or file"),
        field("file", Type::text, "", "", {},
              "a text file of vertices, one \"x y\" or \"x,y\" per line (m), '#' comments; exactly one of "
              "points and file")}));
    t.emplace("ib2d", make_ib2d_object());
    t.emplace("schedules", make_schedule());
    return t;
  }();
  const auto found = tables.find(type);
  if (found == tables.end()) throw std::logic_error("no [[objects]] table '" + type + "'");
  return found->second;
}

jellyfish::ObstacleSpec read_obstacle(const config::Config& o, const std::string& type, const std::string& where) {
  const Reader r(o, object_parameters(type));
  require_known_fields(o, r.table(), where);
  jellyfish::ObstacleSpec spec;
  spec.name = where;
  spec.shape = type == "circle" ? jellyfish::ObstacleShape::circle
               : type == "box"  ? jellyfish::ObstacleShape::box
                                : jellyfish::ObstacleShape::polygon;
  read_shape(r, where, spec);
  if (o.has("stiffness") && o.has("tether_stiffness"))
    throw InputError(where + ": give either 'tether_stiffness' (N/m² per metre of outline) or 'stiffness' (N/m per "
                             "marker), not both");
  if (o.has("stiffness")) spec.tether_stiffness_n_per_m = r.number("stiffness");
  if (o.has("tether_stiffness")) spec.tether_stiffness_n_per_m2 = r.number("tether_stiffness");
  if (o.has("velocity")) spec.motion.velocity_m_per_s = r.vec2("velocity");
  if (o.has("amplitude")) spec.motion.amplitude_m = r.vec2("amplitude");
  if (o.has("frequency")) spec.motion.frequency_hz = r.number("frequency");
  validate_input(spec);
  return spec;
}

/// An IB2d structure: `files` = "path/stem" (IB2d's .vertex, .spring, .d_spring, .beam,
/// .nonInv_beam, .target; relative to the working directory) or `model` = "hoover-miller" generated
/// at `resolution` (IB2d's N); moved by `offset`; its springs scheduled by [[objects.schedules]].
jellyfish::Ib2dObjectSpec read_ib2d_object(const config::Config& o, const std::string& where,
                                           const coupling::TankSpec& tank) {
  const Reader r(o, object_parameters("ib2d"));
  require_known_fields(o, r.table(), where);
  jellyfish::Ib2dObjectSpec spec;
  spec.name = where;
  std::optional<std::array<int, 2>> muscles;  ///< a generated model's muscle springs
  if (o.has("files") == o.has("model"))
    throw InputError(where + ": an ib2d object needs exactly one of 'files' = \"path/stem\" (IB2d's files) or "
                             "'model' = \"hoover-miller\" (or \"hoover-miller-consistent\", its muscles per unit length)");
  if (o.has("files")) {
    if (o.has("resolution")) throw InputError(where + ": 'resolution' goes with 'model', not with 'files'");
    const std::string stem = r.text("files");
    if (stem.empty()) throw InputError(where + ": field 'files' is empty; give the path and stem, e.g. \"ib2d/jelly256\"");
    spec.structure = io::read_ib2d_structure(stem);
    for (const std::filesystem::path& file : io::ib2d_files_present(stem)) spec.files.push_back(file.string());
  } else {
    const jellyfish::HooverMillerBell bell = generated_model(r, where, tank);
    spec.structure = bell.structure;
    muscles = std::array<int, 2>{bell.first_muscle_spring, static_cast<int>(bell.structure.springs.size()) - 1};
  }
  if (o.has("offset")) spec.offset_m = r.vec2("offset");
  const std::size_t schedules = o.has("schedules") ? o.array_size("schedules") : 0;  // optional (docs/ib2d.md)
  for (std::size_t k = 0; k < schedules; ++k)
    spec.schedules.push_back(
        read_schedule(o.element("schedules", k), where + ": schedules[" + std::to_string(k) + "]", muscles));
  validate_input(spec);
  return spec;
}

std::string objects_reference_markdown() {
  const std::string top_level = "\n### Top level\n";
  std::string page;
  for (const std::string& type : object_types()) {
    std::string section = object_parameters(type).reference_markdown();
    std::string heading = "\n### [[objects]] type = \"" + type + "\"\n";
    if (type == "jellyfish")
      heading += "\nAnother jellyfish: every [jellyfish] field above may be given and overrides the scene's.\n";
    if (section.starts_with(top_level)) section.replace(0, top_level.size(), heading);
    page += section;
  }
  std::string schedules = object_parameters("schedules").reference_markdown();
  if (schedules.starts_with(top_level))
    schedules.replace(0, top_level.size(), "\n### [[objects.schedules]] of an ib2d object\n");
  return page + schedules;
}

}  // namespace jellysim::scene
