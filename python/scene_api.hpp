#pragma once
// jellysim.load_scene, jellysim.run_experiment and the exceptions (docs/python.md): the CLI's
// configuration resolution (defaults + scene file or TOML text + key=value overrides) for Python.
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "simulation.hpp"

namespace jellysim::python {

namespace py = pybind11;

/// Defines jellysim.InputError (ValueError with .message, .field, .range) and jellysim.RunError
/// (RuntimeError) in `module` and translates the library's InputError and RunError to them.
void register_exceptions(py::module_& module);

/// Overrides as the CLI's --set assignments: a dict {key: value} and keyword arguments whose `__`
/// stands for `.` (jellyfish__frequency=0.9 is jellyfish.frequency=0.9). Values: bool, int, float,
/// str (as typed after --set key=), or lists of them.
std::vector<std::string> override_assignments(const py::object& overrides, const py::kwargs& kwargs);

/// jellysim.load_scene: `source` a path (str or os.PathLike) or TOML text (a str holding '=' or a
/// line break), or None for the built-in scene.
Scene load_scene(const py::object& source, const py::object& overrides);

/// jellysim.run_experiment: runs experiment `name` (or `simulate`, `run`) into `out` as
/// `jellysim experiment`/`simulate` do, without the GIL; returns summary.json as a dict. Raises
/// RunError (its .summary the dict) when the run failed. `progress` (None or a callable) hears
/// `--progress json`'s objects as dicts; an exception it raises stops the run at its next step
/// boundary (summary.json's status "interrupted") and is raised when the run has stopped.
py::dict run_experiment(const std::string& name, const py::object& out, const py::object& scene,
                        const py::object& overrides, const py::object& progress, const py::kwargs& kwargs);

/// A JSON object as a Python dict (json.loads of its text).
py::object json_dict(const nlohmann::ordered_json& value);

/// jellysim.optimize: `jellysim optimize` with the plan a dict or a path (docs/control.md), into
/// `out` (default out/optimize), without the GIL; returns summary.json as a dict.
py::dict optimize(const py::object& plan, const py::object& out, bool quiet);

}  // namespace jellysim::python
