#include "input_script.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "jellysim/core/errors.hpp"

namespace jellysim::viewer {

namespace {

constexpr int kDefaultDragMoves = 10;

/// One statement's words and where it came from, for error messages.
struct Statement {
  std::vector<std::string> words;
  std::string where;  ///< "SOURCE, line N"
  std::string text;
};

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

std::vector<Statement> split_statements(const std::string& text, const std::string& source) {
  std::vector<Statement> out;
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    line = line.substr(0, line.find('#'));
    std::istringstream parts(line);
    std::string part;
    while (std::getline(parts, part, ';')) {
      part = trim(part);
      if (part.empty()) continue;
      Statement st{{}, source + ", line " + std::to_string(number), part};
      std::istringstream words(part);
      for (std::string w; words >> w;) st.words.push_back(w);
      out.push_back(std::move(st));
    }
  }
  return out;
}

[[noreturn]] void fail(const Statement& st, const std::string& what) {
  throw InputError(st.where + ": '" + st.text + "': " + what);
}

double number_at(const Statement& st, std::size_t i, const char* what) {
  if (i >= st.words.size()) fail(st, std::string("missing ") + what);
  try {
    std::size_t used = 0;
    const double v = std::stod(st.words[i], &used);
    if (used != st.words[i].size() || !std::isfinite(v)) throw std::invalid_argument("");
    return v;
  } catch (const std::exception&) {
    fail(st, std::string(what) + " must be a number, got '" + st.words[i] + "'");
  }
}

long frame_of(const Statement& st) {
  const double f = number_at(st, 0, "frame number (first word)");
  if (f < 0 || f != std::floor(f) || f > 1e9) fail(st, "frame must be an integer in [0, 1e9]");
  return static_cast<long>(f);
}

int button_at(const Statement& st, std::size_t i) {
  if (i >= st.words.size() || st.words[i] == "left") return 0;
  if (st.words[i] == "right") return 1;
  fail(st, "button must be left or right, got '" + st.words[i] + "'");
}

void expect_words(const Statement& st, std::size_t min, std::size_t max, const char* usage) {
  if (st.words.size() < min || st.words.size() > max) fail(st, std::string("usage: FRAME ") + usage);
}

InputEvent mouse_event(const Statement& st, long frame, EventKind kind, std::size_t x_word) {
  InputEvent e;
  e.frame = frame;
  e.kind = kind;
  e.x = number_at(st, x_word, "X");
  e.y = number_at(st, x_word + 1, "Y");
  e.text = st.text;
  return e;
}

void add_drag(const Statement& st, long frame, std::vector<InputEvent>& out) {
  expect_words(st, 6, 7, "drag X0 Y0 X1 Y1 [MOVES]");
  const double x0 = number_at(st, 2, "X0"), y0 = number_at(st, 3, "Y0");
  const double x1 = number_at(st, 4, "X1"), y1 = number_at(st, 5, "Y1");
  const double moves = st.words.size() == 7 ? number_at(st, 6, "MOVES") : kDefaultDragMoves;
  if (moves < 1 || moves > 10000 || moves != std::floor(moves)) fail(st, "MOVES must be an integer in [1, 10000]");
  InputEvent press = mouse_event(st, frame, EventKind::press, 2);
  out.push_back(press);
  const int n = static_cast<int>(moves);
  for (int k = 1; k <= n; ++k) {
    InputEvent mv = press;
    mv.kind = EventKind::move;
    mv.frame = frame + k;
    mv.x = x0 + (x1 - x0) * k / n;
    mv.y = y0 + (y1 - y0) * k / n;
    out.push_back(mv);
  }
  InputEvent release = out.back();
  release.kind = EventKind::release;
  out.push_back(release);
}

void add_set(const Statement& st, long frame, std::vector<InputEvent>& out) {
  expect_words(st, 4, 5, "set NAME [INDEX] VALUE");
  InputEvent e;
  e.frame = frame;
  e.kind = EventKind::set;
  e.name = st.words[2];
  e.text = st.text;
  const auto& names = settable_parameters();
  if (std::find(names.begin(), names.end(), e.name) == names.end()) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    fail(st, "unknown parameter '" + e.name + "' (allowed: " + list + ")");
  }
  if (st.words.size() == 5) {
    const double index = number_at(st, 3, "INDEX");
    if (index < 0 || index != std::floor(index) || index > 1e6) fail(st, "INDEX must be a jellyfish number ≥ 0");
    e.index = static_cast<int>(index);
  }
  e.value = number_at(st, st.words.size() - 1, "VALUE");
  out.push_back(e);
}

void add_statement(const Statement& st, std::vector<InputEvent>& out) {
  const long frame = frame_of(st);
  if (st.words.size() < 2) fail(st, "missing event after the frame number");
  const std::string& verb = st.words[1];
  InputEvent e;
  e.frame = frame;
  e.text = st.text;
  if (verb == "pause" || verb == "step") {
    expect_words(st, 2, 2, "pause | step");
    e.kind = verb == "pause" ? EventKind::pause : EventKind::step;
    out.push_back(e);
  } else if (verb == "key" || verb == "mark") {
    expect_words(st, 3, 3, verb == "key" ? "key NAME" : "mark LABEL");
    e.kind = verb == "key" ? EventKind::key : EventKind::mark;
    e.name = st.words[2];
    out.push_back(e);
  } else if (verb == "press" || verb == "release" || verb == "move") {
    expect_words(st, 4, verb == "move" ? 4 : 5, "press|release X Y [left|right] or move X Y");
    const EventKind kind = verb == "press" ? EventKind::press : verb == "release" ? EventKind::release : EventKind::move;
    InputEvent m = mouse_event(st, frame, kind, 2);
    m.button = button_at(st, 4);
    out.push_back(m);
  } else if (verb == "click") {
    expect_words(st, 4, 5, "click X Y [left|right]");
    InputEvent press = mouse_event(st, frame, EventKind::press, 2);
    press.button = button_at(st, 4);
    InputEvent release = press;
    release.kind = EventKind::release;
    release.frame = frame + 1;
    out.push_back(press);
    out.push_back(release);
  } else if (verb == "drag") {
    add_drag(st, frame, out);
  } else if (verb == "set") {
    add_set(st, frame, out);
  } else {
    fail(st, "unknown event '" + verb + "' (allowed: pause, step, key, press, move, release, click, drag, set, mark)");
  }
}

}  // namespace

const std::vector<std::string>& settable_parameters() {
  static const std::vector<std::string> names{"frequency",         "gamma",          "stiffness",
                                              "viscosity",         "noise.structural", "noise.compression",
                                              "noise.unstructured", "speed"};
  return names;
}

std::vector<InputEvent> parse_input_script(const std::string& text, const std::string& source) {
  std::vector<InputEvent> events;
  for (const Statement& st : split_statements(text, source)) add_statement(st, events);
  std::stable_sort(events.begin(), events.end(),
                   [](const InputEvent& a, const InputEvent& b) { return a.frame < b.frame; });
  return events;
}

}  // namespace jellysim::viewer
