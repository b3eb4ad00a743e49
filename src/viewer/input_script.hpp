#pragma once
// Timed input events for the viewer (tests, benchmarks, demos): a small text format read from
// `--script FILE` or `--inject "..."`. One event per line or separated by ';', '#' starts a comment:
//
//   FRAME pause                      toggle pause (same as the space key)
//   FRAME step                       one simulation step (same as the S key)
//   FRAME key NAME                   a key press: space, s, r, v, p, q, tab, escape, or one letter
//   FRAME press X Y [left|right]     mouse button down at window pixel (X, Y), y down
//   FRAME move X Y                   mouse moves to (X, Y)
//   FRAME release X Y [left|right]   mouse button up
//   FRAME click X Y [left|right]     press at FRAME, release at FRAME + 1
//   FRAME drag X0 Y0 X1 Y1 [N]       left press at (X0, Y0), N moves (default 10) to (X1, Y1), release
//   FRAME set NAME [INDEX] VALUE     a parameter as its slider sets it: frequency, gamma, stiffness
//                                    (INDEX = jellyfish, default 0), viscosity, noise.structural,
//                                    noise.compression, noise.unstructured, speed (target sim rate)
//   FRAME mark LABEL                 only records the state in the stats timeline
//
// Every event also records the state (time, paused, positions) in the --stats timeline. Pure text
// handling, no window: parse errors name the line and what is allowed.
#include <string>
#include <vector>

namespace jellysim::viewer {

enum class EventKind { pause, step, key, press, move, release, set, mark };

struct InputEvent {
  long frame = 0;
  EventKind kind = EventKind::mark;
  double x = 0.0, y = 0.0;   ///< window pixels (press, move, release)
  int button = 0;            ///< 0 left, 1 right
  std::string name;          ///< key name, parameter name or mark label
  int index = 0;             ///< jellyfish index for `set`
  double value = 0.0;        ///< value for `set`
  std::string text;          ///< the source text (for the timeline)
};

/// Parses the script; expands click and drag into press/move/release. Events are sorted by frame
/// (stable: same-frame events keep their order). Throws InputError naming `source`, the line and
/// what is wrong.
std::vector<InputEvent> parse_input_script(const std::string& text, const std::string& source);

/// Parameter names accepted by `set`.
const std::vector<std::string>& settable_parameters();

}  // namespace jellysim::viewer
