// jellysim.optimize (docs/python.md, docs/control.md): `jellysim optimize` from Python, the plan a
// dict (written as the plan file's TOML) or a path, run without the GIL; returns summary.json.
#include "scene_api.hpp"

#include <pybind11/stl.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "jellysim/core/errors.hpp"
#include "jellysim/experiments/optimize.hpp"
#include "jellysim/io/output.hpp"

namespace jellysim::python {
namespace {

std::string quoted(const std::string& text) {
  std::string q = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') q += '\\';
    q += c;
  }
  return q + "\"";
}

/// A plan value as TOML: bool, int, float, str or a list of them.
std::string toml_value(const py::handle& v, const std::string& key) {
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::int_>(v)) return std::to_string(v.cast<long long>());
  if (py::isinstance<py::float_>(v)) return io::format_double(v.cast<double>());
  if (py::isinstance<py::str>(v)) return quoted(v.cast<std::string>());
  if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) {
    std::string text = "[";
    for (const py::handle& item : v) text += (text.size() > 1 ? ", " : "") + toml_value(item, key);
    return text + "]";
  }
  throw InputError("plan field '" + key + "': " + py::str(py::repr(v)).cast<std::string>() +
                   " is not a bool, number, str or list");
}

/// The plan dict as the plan file's text: its values first, then its tables ([set], [variables], ...).
std::string plan_text(const py::dict& plan) {
  std::string top, tables;
  for (const auto& [k, v] : plan) {
    const std::string key = py::str(k);
    if (py::isinstance<py::dict>(v)) {
      tables += "[" + key + "]\n";
      for (const auto& [sk, sv] : v.cast<py::dict>()) tables += quoted(py::str(sk)) + " = " + toml_value(sv, key + "." + std::string(py::str(sk))) + "\n";
    } else {
      top += key + " = " + toml_value(v, key) + "\n";
    }
  }
  return top + tables;
}

}  // namespace

py::dict optimize(const py::object& plan, const py::object& out, bool quiet) {
  const experiments::OptimizePlan parsed =
      py::isinstance<py::dict>(plan)
          ? experiments::parse_optimize_plan(plan_text(plan.cast<py::dict>()), std::filesystem::current_path() / "plan (dict)")
          : experiments::read_optimize_plan(py::str(py::module_::import("os").attr("fspath")(plan)).cast<std::string>());
  const std::string dir = out.is_none() ? "out/optimize" : py::str(py::module_::import("os").attr("fspath")(out)).cast<std::string>();
  {
    py::gil_scoped_release released;
    experiments::run_optimize(parsed, dir, quiet);
  }
  std::ifstream in(std::filesystem::path(dir) / "summary.json");
  std::stringstream text;
  text << in.rdbuf();
  return py::module_::import("json").attr("loads")(text.str());
}

}  // namespace jellysim::python
