// jellysim.load_scene, jellysim.run_experiment and the exceptions (scene_api.hpp).
#include "scene_api.hpp"

#include <pybind11/eval.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "jellysim/core/errors.hpp"
#include "jellysim/experiments/experiment.hpp"

namespace jellysim::python {

namespace {

// The exception classes, defined in Python so that they carry attributes.
constexpr const char* kExceptions = R"(
class InputError(ValueError):
    """Bad input, as the CLI's exit code 2: .message (the CLI's text), .field (the key it names or
    None) and .range (the allowed range or values as the message gives them, or None)."""
    def __init__(self, message, field=None, range=None):
        super().__init__(message)
        self.message = message
        self.field = field
        self.range = range

class RunError(RuntimeError):
    """A run that started and failed (a diverged simulation): .message, and for run_experiment
    .summary (summary.json as a dict)."""
    def __init__(self, message, summary=None):
        super().__init__(message)
        self.message = message
        self.summary = summary
)";

/// The first capture of `pattern` in `text`, or None.
py::object capture(const std::string& text, const std::regex& pattern) {
  std::smatch m;
  if (std::regex_search(text, m, pattern)) return py::str(m[1].str());
  return py::none();
}

/// The field an InputError names: "field 'KEY'" or "--set 'KEY=..." / "--set KEY=...".
py::object field_of(const std::string& message) {
  static const std::regex field(R"(field '([^']+)')"), set(R"(--set '?([^'=: ]+))");
  py::object f = capture(message, field);
  return f.is_none() ? capture(message, set) : f;
}

/// The allowed range an InputError gives: "range [a, b]", "in (a, b)", or "not one of: a, b".
py::object range_of(const std::string& message) {
  static const std::regex interval(R"(\b(?:range|in) ([\[(][^\])]*[\])]))"), choices(R"(not one of: (.*)$)");
  py::object r = capture(message, interval);
  return r.is_none() ? capture(message, choices) : r;
}

/// TOML text of an override value as typed after --set key= (strings as they are at the top level,
/// quoted inside lists).
std::string value_text(const py::handle& value, bool nested) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)) return py::str(py::repr(value));
  if (py::isinstance<py::str>(value)) {
    const std::string s = value.cast<std::string>();
    if (!nested) return s;
    return py::module_::import("json").attr("dumps")(s).cast<std::string>();  // a TOML basic string
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    std::string text = "[";
    for (const py::handle& item : value) text += (text.size() > 1 ? ", " : "") + value_text(item, true);
    return text + "]";
  }
  throw InputError("override value " + py::str(py::repr(value)).cast<std::string>() +
                   ": expected a bool, int, float, str or a list of them");
}

std::string key_text(const py::handle& key) {
  if (!py::isinstance<py::str>(key)) throw InputError("override key " + py::str(py::repr(key)).cast<std::string>() + " is not a str");
  return key.cast<std::string>();
}

/// "out/NAME" when out is None, else the path as text (str or os.PathLike).
std::string path_text(const py::object& path) { return py::str(py::module_::import("os").attr("fspath")(path)); }

/// The experiment a name runs: the CLI's command names map to their definitions.
const experiments::Experiment& experiment_named(const std::string& name) {
  return experiments::find_experiment(name == "simulate" ? "jellyfish" : name == "run" ? "animation" : name);
}

py::dict read_summary(const std::filesystem::path& dir) {
  std::ifstream in(dir / "summary.json");
  std::stringstream text;
  text << in.rdbuf();
  return py::module_::import("json").attr("loads")(text.str());
}

}  // namespace

void register_exceptions(py::module_& module) {
  py::exec(kExceptions, module.attr("__dict__"));
  // Owned references kept until exit (the module is never unloaded).
  static const py::handle input_error = py::object(module.attr("InputError")).release();
  static const py::handle run_error = py::object(module.attr("RunError")).release();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      const std::string message = e.what();
      const py::object error = input_error(message, field_of(message), range_of(message));
      PyErr_SetObject(input_error.ptr(), error.ptr());
    } catch (const RunError& e) {
      PyErr_SetObject(run_error.ptr(), run_error(std::string(e.what())).ptr());
    }
  });
}

std::vector<std::string> override_assignments(const py::object& overrides, const py::kwargs& kwargs) {
  std::vector<std::string> sets;
  if (!overrides.is_none())
    for (const auto& [key, value] : overrides.cast<py::dict>()) sets.push_back(key_text(key) + "=" + value_text(value, false));
  for (const auto& [key, value] : kwargs) {
    std::string k = key_text(key);
    for (std::size_t at = k.find("__"); at != std::string::npos; at = k.find("__", at + 1)) k.replace(at, 2, ".");
    sets.push_back(k + "=" + value_text(value, false));
  }
  return sets;
}

Scene load_scene(const py::object& source, const py::object& overrides) {
  const std::vector<std::string> sets = override_assignments(overrides, py::kwargs());
  if (source.is_none()) return resolve_scene(nullptr, "", sets);
  if (py::isinstance<py::str>(source)) {
    const std::string text = source.cast<std::string>();
    if (text.find_first_of("=\n") != std::string::npos) {
      const io::Config toml = io::Config::parse(text, "scene text");
      return resolve_scene(&toml, "scene text", sets);
    }
  }
  const std::string path = path_text(source);
  const io::Config file = io::Config::load(path);
  return resolve_scene(&file, path, sets);
}

py::dict run_experiment(const std::string& name, const py::object& out, const py::object& scene,
                        const py::object& overrides, const py::kwargs& kwargs) {
  const experiments::Experiment& e = experiment_named(name);
  experiments::Context ctx{experiments::default_config(e), {}};
  if (!scene.is_none()) ctx.config.merge(io::Config::load(path_text(scene)));
  apply_overrides(ctx.config, override_assignments(overrides, kwargs));
  auto run = e.prepare(ctx);  // validates everything before anything is written
  const io::OutputDir dir = io::OutputDir::for_run(out.is_none() ? "out/" + e.name : path_text(out), e.name);
  experiments::Outcome outcome;
  {
    py::gil_scoped_release released;
    outcome = run(dir);
    dir.finish_manifest();
  }
  py::dict summary = read_summary(dir.path());
  if (!outcome.failure.empty()) {
    const py::object error = py::module_::import("jellysim").attr("RunError")(outcome.failure, summary);
    PyErr_SetObject(error.get_type().ptr(), error.ptr());
    throw py::error_already_set();
  }
  return summary;
}

}  // namespace jellysim::python
