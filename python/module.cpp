// The Python module `jellysim` (docs/python.md): load_scene, Simulation, run_experiment. Stepping
// and runs release the GIL; grid fields are read-only views of the solver's storage, everything
// else is copied.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <stdexcept>

#include "jellysim/experiments/progress.hpp"

#include "arrays.hpp"
#include "scene_api.hpp"
#include "simulation.hpp"

namespace py = pybind11;
namespace jp = jellysim::python;

namespace {

/// The Python-side Simulation: the C++ state and a flag that refuses a second thread while one
/// steps without the GIL.
class PySimulation {
 public:
  explicit PySimulation(const jp::Scene& scene) : sim_(scene) {}

  /// Runs f on the state, refusing when another thread is stepping it.
  template <typename F>
  decltype(auto) use(F&& f) {
    if (busy_.exchange(true)) throw std::runtime_error("the Simulation is being stepped in another thread");
    struct Done {
      std::atomic<bool>& flag;
      ~Done() { flag = false; }
    } done{busy_};
    return f(sim_);
  }
  /// Steps (f) without the GIL.
  template <typename F>
  void step_released(F&& f) {
    use([&](jp::Simulation& s) {
      py::gil_scoped_release released;
      f(s);
    });
  }

 private:
  jp::Simulation sim_;
  std::atomic<bool> busy_{false};
};

PySimulation& self_of(const py::object& self) { return self.cast<PySimulation&>(); }

/// Python's negative indices for a recorded frame.
std::size_t frame_index(long frame, std::size_t count) {
  const long k = frame < 0 ? frame + static_cast<long>(count) : frame;
  if (k < 0 || k >= static_cast<long>(count))
    throw py::index_error("frame " + std::to_string(frame) + " out of range (" + std::to_string(count) + " recorded)");
  return static_cast<std::size_t>(k);
}

/// metrics.csv's columns (experiments::write_metrics_csv), each a float64 array over the frames.
py::dict metrics_dict(const std::vector<jellysim::jellyfish::MetricsRow>& rows) {
  using Row = jellysim::jellyfish::MetricsRow;
  static const std::pair<const char*, double Row::*> columns[] = {
      {"t", &Row::t}, {"position", &Row::position}, {"velocity", &Row::velocity}, {"acceleration", &Row::acceleration},
      {"volume", &Row::volume}, {"aperture_area", &Row::aperture_area}, {"volume_ratio", &Row::volume_ratio},
      {"aperture_ratio", &Row::aperture_ratio}, {"thrust", &Row::thrust}, {"lateral", &Row::lateral},
      {"daniel_velocity", &Row::daniel_velocity}, {"daniel_position", &Row::daniel_position}};
  py::dict d;
  for (const auto& [name, member] : columns) {
    std::vector<double> values;
    for (const Row& r : rows) values.push_back(r.*member);
    d[name] = jp::vector_array(values);
  }
  return d;
}

/// advance() without the GIL, taking it back at each frame to see whether a signal (Ctrl-C) came and
/// to call `progress` (optional) with `--progress json`'s object as a dict, at most five a second
/// plus the last. An exception the callback raises stops the run at that frame and propagates.
void advance(PySimulation& self, double seconds, const py::object& progress) {
  jellysim::experiments::ProgressTracker tracker("simulate");
  bool done = true;
  self.step_released([&](jp::Simulation& s) {
    done = s.advance(seconds, [&] {
      py::gil_scoped_acquire held;
      if (PyErr_CheckSignals() != 0) return true;
      if (progress.is_none()) return false;
      const nlohmann::ordered_json line = tracker.simulation(s.time_s(), s.target_s(), s.steps());
      if (line.is_null()) return false;
      try {
        progress(jp::json_dict(line));
      } catch (py::error_already_set& e) {
        e.restore();  // raised again below, as a signal's exception is
        return true;
      }
      return false;
    });
  });
  if (!done) throw py::error_already_set();  // the signal handler's or the callback's exception
}

/// The flow on the MAC grid: read-only views of u, v, pressure and their sample coordinates.
py::dict velocity_field(const py::object& self) {
  return self_of(self).use([&](jp::Simulation& s) {
    const jellysim::fluid::FlowState& flow = s.swim().flow();
    const jellysim::fluid::Field &u = flow.velocity.u, &v = flow.velocity.v, &p = flow.pressure;
    py::dict d;
    d["u"] = jp::field_view(u, self);
    d["v"] = jp::field_view(v, self);
    d["pressure"] = jp::field_view(p, self);
    d["x_faces"] = jp::sample_coordinates(u, 0);
    d["y_centres"] = jp::sample_coordinates(u, 1);
    d["x_centres"] = jp::sample_coordinates(v, 0);
    d["y_faces"] = jp::sample_coordinates(v, 1);
    return d;
  });
}

py::tuple mesh(const py::object& self, long frame) {
  return self_of(self).use([&](jp::Simulation& s) {
    jellysim::geometry::FrameGeometry g;
    const std::size_t k = frame_index(frame, s.frames().size());
    {
      py::gil_scoped_release released;
      g = s.mesh(k);
    }
    return py::make_tuple(jp::vertices_array(g.mesh), jp::triangles_array(g.mesh));
  });
}

py::dict scene_config(const jp::Scene& scene) {
  return py::module_::import("json").attr("loads")(scene.config.to_json().dump());
}

void bind_scene(py::module_& m) {
  py::class_<jp::Scene>(m, "Scene", "A resolved, validated jellyfish scene (jellysim.load_scene).")
      .def_property_readonly("config", &scene_config, "The resolved configuration as a dict (summary.json's config).")
      .def_property_readonly("duration", [](const jp::Scene& s) { return s.settings.duration_s; }, "s")
      .def_property_readonly("frame_interval", [](const jp::Scene& s) { return s.settings.frame_interval_s; }, "s")
      .def("__repr__", [](const jp::Scene& s) {
        return "<jellysim.Scene " + std::to_string(s.settings.tank.cells_x) + "x" +
               std::to_string(s.settings.tank.cells_y) + " cells, " + std::to_string(s.settings.school.size()) +
               " jellyfish>";
      });
  m.def("load_scene", &jp::load_scene, py::arg("source") = py::none(), py::arg("overrides") = py::none(),
        "The built-in jellyfish scene, a scene file (path) or TOML text laid over it, then overrides "
        "{key: value} (the CLI's --set key=value); validated as `jellysim simulate` does. Raises InputError.");
}

void bind_simulation(py::module_& m) {
  py::class_<PySimulation>(m, "Simulation", "A jellyfish scene stepped on `jellysim simulate`'s frame clock.")
      .def(py::init<const jp::Scene&>(), py::arg("scene"))
      .def("step", [](PySimulation& s) { s.step_released([](jp::Simulation& x) { x.step(); }); },
           "One coupled step toward the next frame time (GIL released).")
      .def("advance", &advance, py::arg("seconds"), py::arg("progress") = py::none(),
           "Steps to the frame nearest the duration asked for, as `simulate --duration` (GIL released; Ctrl-C stops "
           "it at a frame). progress(dict) (optional) hears `--progress json`'s objects: stage, time, duration, "
           "fraction, steps, eta_seconds; an exception it raises stops the run there.")
      .def_property_readonly("time", [](PySimulation& s) { return s.use([](jp::Simulation& x) { return x.time_s(); }); }, "s")
      .def_property_readonly("steps", [](PySimulation& s) { return s.use([](jp::Simulation& x) { return x.steps(); }); })
      .def_property_readonly("frame_count", [](PySimulation& s) { return s.use([](jp::Simulation& x) { return x.frames().size(); }); })
      .def("markers", [](PySimulation& s, std::size_t j) { return s.use([&](jp::Simulation& x) { return jp::points_array(x.markers(j)); }); },
           py::arg("jellyfish") = 0, "(N, 2) float64 copy: the umbrella points, then each tentacle (slices.csv's order), m.")
      .def("velocity_field", &velocity_field, "Read-only views of u, v, pressure on the MAC grid and their coordinates.")
      .def("metrics", [](PySimulation& s) { return s.use([](jp::Simulation& x) { return metrics_dict(x.metrics()); }); },
           "metrics.csv's columns over the recorded frames, float64 arrays.")
      .def("mesh", &mesh, py::arg("frame") = -1, "(vertices (V, 3) float64, triangles (T, 3) int64) of a recorded frame.");
  m.def("_live_simulations", &jp::Simulation::live_count, "Simulations alive now (for the leak test).");
}

}  // namespace

PYBIND11_MODULE(jellysim, m) {
  m.doc() = "jellysim: a physically simulated jellyfish (docs/python.md)";
  m.attr("__version__") = JELLYSIM_VERSION;
  jp::register_exceptions(m);
  bind_scene(m);
  bind_simulation(m);
  m.def("run_experiment", &jp::run_experiment, py::arg("name"), py::kw_only(), py::arg("out") = py::none(),
        py::arg("scene") = py::none(), py::arg("overrides") = py::none(), py::arg("progress") = py::none(),
        "Runs an experiment (or `simulate`, `run`) into out (default out/NAME) and returns summary.json as a dict; "
        "keyword overrides use __ for . (jellyfish__frequency=0.9). progress(dict) (optional) hears `--progress "
        "json`'s objects (stages simulate, and render for `run`); an exception it raises is raised after the run.");
  m.def("optimize", &jp::optimize, py::arg("plan"), py::kw_only(), py::arg("out") = py::none(), py::arg("quiet") = true,
        "Runs `jellysim optimize`: plan a dict (the plan file's fields and tables) or a plan file's path; writes "
        "evaluations.csv, best.toml, progress.png, summary.json into out (default out/optimize; an earlier run "
        "there is resumed) and returns summary.json as a dict (docs/control.md).");
}
