// jellysim.load_scene, jellysim.run_experiment and the exceptions (scene_api.hpp).
#include "scene_api.hpp"

#include <pybind11/eval.h>

#include <algorithm>
#include <csignal>
#include <functional>
#include <optional>
#include <cctype>
#include <fstream>
#include <sstream>

#include "jellysim/core/errors.hpp"
#include "jellysim/core/interrupt.hpp"
#include "jellysim/experiments/experiment.hpp"
#include "jellysim/experiments/progress.hpp"
#include "jellysim/scene/resolve.hpp"

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

// The fields and ranges are found by plain string searching: std::regex recurses once per character
// in libstdc++ and overflows the stack on a message quoting a long key or value (issue 35, item 2).

/// The run of characters from `from` up to (not including) any of `stops`, or None when empty.
py::object run_until(const std::string& text, std::size_t from, const char* stops) {
  const std::size_t end = std::min(text.find_first_of(stops, from), text.size());
  return end > from ? py::object(py::str(text.substr(from, end - from))) : py::object(py::none());
}

/// The first non-empty quoted name after "field '": "field 'KEY'".
py::object quoted_field(const std::string& message) {
  for (std::size_t at = message.find("field '"); at != std::string::npos; at = message.find("field '", at + 1)) {
    const std::size_t from = at + 7, end = message.find('\'', from);
    if (end != std::string::npos && end > from) return py::str(message.substr(from, end - from));
  }
  return py::none();
}

/// The key after "--set ": "--set 'KEY=..." or "--set KEY=...".
py::object set_key(const std::string& message) {
  for (std::size_t at = message.find("--set "); at != std::string::npos; at = message.find("--set ", at + 1)) {
    std::size_t from = at + 6;
    if (from < message.size() && message[from] == '\'') ++from;
    if (py::object key = run_until(message, from, "'=: "); !key.is_none()) return key;
  }
  return py::none();
}

/// The field an InputError names: "field 'KEY'" or "--set 'KEY=..." / "--set KEY=...".
py::object field_of(const std::string& message) {
  py::object f = quoted_field(message);
  return f.is_none() ? set_key(message) : f;
}

/// An interval "[a, b]" / "(a, b)" starting at `from` (brackets without ] or ) inside), or None.
py::object interval_at(const std::string& text, std::size_t from) {
  if (from >= text.size() || (text[from] != '[' && text[from] != '(')) return py::none();
  const std::size_t end = text.find_first_of("])", from + 1);
  return end == std::string::npos ? py::object(py::none()) : py::object(py::str(text.substr(from, end + 1 - from)));
}

bool word_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; }

/// The first interval after the word "range" or "in" and a space: "range [a, b]", "in (a, b)".
py::object interval_of(const std::string& message) {
  for (std::size_t at = 0; at < message.size(); ++at) {
    if (at > 0 && word_char(message[at - 1])) continue;
    for (const std::string word : {"range ", "in "})
      if (message.compare(at, word.size(), word) == 0)
        if (py::object r = interval_at(message, at + word.size()); !r.is_none()) return r;
  }
  return py::none();
}

/// The allowed range an InputError gives: "range [a, b]", "in (a, b)", or "not one of: a, b".
py::object range_of(const std::string& message) {
  py::object r = interval_of(message);
  if (!r.is_none()) return r;
  const std::size_t last_line = message.rfind('\n');
  const std::size_t at = message.find("not one of: ", last_line == std::string::npos ? 0 : last_line + 1);
  return at == std::string::npos ? py::object(py::none()) : py::object(py::str(message.substr(at + 12)));
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
      const config::Config toml = config::Config::parse(text, "scene text");
      return resolve_scene(&toml, "scene text", sets);
    }
  }
  const std::string path = path_text(source);
  const config::Config file = config::Config::load(path);
  return resolve_scene(&file, path, sets);
}

py::object json_dict(const nlohmann::ordered_json& value) {
  return py::module_::import("json").attr("loads")(value.dump());
}

namespace {

/// run_experiment's progress callback, called from the run's threads: each report takes the GIL;
/// the first exception the callback raises is kept and asks the run to stop.
struct PythonProgress {
  explicit PythonProgress(py::object f) : callback(std::move(f)) {}
  py::object callback;
  experiments::ProgressTracker simulate{"simulate"}, render{"render"};
  std::optional<py::error_already_set> error;

  void report(const std::function<nlohmann::ordered_json()>& line_of) {
    py::gil_scoped_acquire held;
    if (callback.is_none() || error) return;
    const nlohmann::ordered_json line = line_of();
    if (line.is_null()) return;
    try {
      callback(json_dict(line));
    } catch (py::error_already_set& e) {
      error = std::move(e);
      core::request_interrupt(SIGINT);  // the run stops at its next step boundary, keeping its files
    }
  }
};

}  // namespace

py::dict run_experiment(const std::string& name, const py::object& out, const py::object& scene,
                        const py::object& overrides, const py::object& progress, const py::kwargs& kwargs) {
  const experiments::Experiment& e = experiment_named(name);
  scene::ConfigSources sources{{}, scene.is_none() ? "" : path_text(scene), "", false,
                               override_assignments(overrides, kwargs)};
  if (!scene.is_none()) sources.scene_file = config::Config::load(sources.scene_name);
  PythonProgress reports(progress);
  PythonProgress* r = &reports;  // the callbacks hold a pointer: no Python object is copied without the GIL
  experiments::Context ctx{
      scene::resolve_config(experiments::default_config(e), sources, "experiment '" + e.name + "'"), {}};
  if (!progress.is_none()) {
    ctx.progress = [r](double t, double duration, std::int64_t steps) {
      r->report([&] { return r->simulate.simulation(t, duration, steps); });
    };
    ctx.render_progress = [r](std::size_t done, std::size_t total) {
      r->report([&] { return r->render.count(done, total, "frames"); });
    };
  }
  auto run = e.prepare(ctx);  // validates everything before anything is written
  const io::OutputDir dir = io::OutputDir::for_run(out.is_none() ? "out/" + e.name : path_text(out), e.name);
  experiments::Outcome outcome;
  {
    py::gil_scoped_release released;
    outcome = experiments::run_guarded(e, ctx, run, dir);
    dir.finish_manifest();
  }
  if (reports.error) {
    core::clear_interrupt();
    reports.error->restore();
    throw py::error_already_set();
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
