#include "jellysim/io/ib2d_files.hpp"

#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <fstream>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "jellysim/core/errors.hpp"
#include "jellysim/io/output.hpp"

namespace jellysim::io {

namespace {

namespace fs = std::filesystem;
using elastic::Ib2dBeam;
using elastic::Ib2dNonInvariantBeam;
using elastic::Ib2dSpring;
using elastic::Ib2dStructure;
using elastic::Ib2dTarget;

/// The degree of nonlinearity a spring may have (IB2d's alpha).
constexpr double kMinDegree = 1.0;
constexpr double kMaxDegree = 10.0;

/// One kind of IB2d file: its extension and the names of its columns, in order.
struct Format {
  std::string_view extension;
  std::vector<std::string_view> columns;
  std::size_t required_columns;  ///< the columns past these are optional (a .spring file's alpha)
};

const Format kVertex{".vertex", {"x", "y"}, 2};
const Format kSpring{".spring", {"master", "slave", "k", "RL", "alpha"}, 4};
const Format kDampedSpring{".d_spring", {"master", "slave", "k", "RL", "b"}, 5};
const Format kBeam{".beam", {"left", "middle", "right", "k", "C"}, 5};
const Format kNonInvariantBeam{".nonInv_beam", {"left", "middle", "right", "k", "Cx", "Cy"}, 6};
const Format kTarget{".target", {"id", "k"}, 2};

/// STEM.ext (appended, not replaced: a stem may hold dots of its own, "jelly.v2").
fs::path file_of(const fs::path& stem, const Format& format) {
  return fs::path(stem.native() + std::string(format.extension));
}

/// "IB2d .spring file 'dir/jelly.spring'"
std::string shown(const fs::path& path, const Format& format) {
  return "IB2d " + std::string(format.extension) + " file '" + path.string() + "'";
}

/// "x y" or "master slave k RL [alpha]"
std::string column_list(const Format& format) {
  std::string list;
  for (std::size_t c = 0; c < format.columns.size(); ++c) {
    if (c > 0) list += ' ';
    list += c < format.required_columns ? std::string(format.columns[c]) : "[" + std::string(format.columns[c]) + "]";
  }
  return list;
}

/// A token as it may appear in a message: at most 40 characters, nothing unprintable.
std::string quoted(std::string_view token) {
  std::string out = "\"";
  for (std::size_t k = 0; k < token.size() && k < 40; ++k) {
    const unsigned char c = static_cast<unsigned char>(token[k]);
    out += c >= 0x20 && c < 0x7f ? static_cast<char>(c) : '?';
  }
  if (token.size() > 40) out += "...";
  return out + '"';
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r'; }

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t at = 0;
  while (true) {
    while (at < line.size() && is_space(line[at])) ++at;
    if (at == line.size()) break;
    const std::size_t begin = at;
    while (at < line.size() && !is_space(line[at])) ++at;
    tokens.push_back(line.substr(begin, at - begin));
  }
  return tokens;
}

std::string type_name(fs::file_type type) {
  switch (type) {
    case fs::file_type::directory: return "a directory";
    case fs::file_type::character: return "a character device";
    case fs::file_type::block: return "a block device";
    case fs::file_type::fifo: return "a named pipe";
    case fs::file_type::socket: return "a socket";
    default: return "not a file of a known type";
  }
}

/// The whole content of `path`, or nothing when the file is absent and `required` is false.
std::optional<std::string> read_text(const fs::path& path, const std::string& file, bool required) {
  std::error_code ec;
  const fs::file_status link = fs::symlink_status(path, ec);
  if (link.type() == fs::file_type::not_found) {
    if (!required) return std::nullopt;
    throw InputError(file + " cannot be read: no such file (the .vertex file is required)");
  }
  if (ec) throw InputError(file + " cannot be read: " + ec.message());
  const fs::file_status status = fs::status(path, ec);
  if (status.type() == fs::file_type::not_found)
    throw InputError(file + " cannot be read: it is a symbolic link to nothing");
  if (ec) throw InputError(file + " cannot be read: " + ec.message());
  if (!fs::is_regular_file(status))
    throw InputError(file + " is not a regular file: it is " + type_name(status.type()));
  const std::uintmax_t bytes = fs::file_size(path, ec);
  if (ec) throw InputError(file + " cannot be read: " + ec.message());
  const std::string too_big = " bytes; at most " + std::to_string(kMaxIb2dFileBytes);
  if (bytes > kMaxIb2dFileBytes) throw InputError(file + " is " + std::to_string(bytes) + too_big);
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(file + " cannot be read: " + os_reason(errno ? errno : EACCES));
  std::string text;
  text.reserve(static_cast<std::size_t>(bytes));
  std::array<char, 1 << 16> buffer;
  while (in) {
    in.read(buffer.data(), buffer.size());
    text.append(buffer.data(), static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxIb2dFileBytes)  // it grew since its size was taken
      throw InputError(file + " is more than " + std::to_string(kMaxIb2dFileBytes) + " bytes");
  }
  if (in.bad()) throw InputError(file + " cannot be read: an I/O error");
  return text;
}

/// One data row of a file, with the checks its values must pass; every failure names the file,
/// the line and the column.
class Row {
 public:
  Row(const std::string& file, const Format& format, std::size_t line, std::vector<std::string_view> tokens,
      std::size_t vertex_count)
      : file_(file), format_(format), line_(line), tokens_(std::move(tokens)), vertex_count_(vertex_count) {}

  std::size_t size() const { return tokens_.size(); }

  /// A finite number.
  double number(std::size_t c) const {
    const std::string_view token = tokens_[c];
    double v = 0.0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
    if (ec == std::errc() && end == token.data() + token.size()) {
      if (std::isfinite(v)) return v;
      fail(c, quoted(token) + " is not a finite number (NaN and infinities are not allowed)");
    }
    if (ec == std::errc::result_out_of_range && end == token.data() + token.size())
      fail(c, quoted(token) + " is too large for a double");
    fail(c, "expected a number, got " + quoted(token));
  }
  /// A number >= 0.
  double non_negative(std::size_t c) const {
    const double v = number(c);
    if (!(v >= 0.0)) fail(c, "must be >= 0, got " + std::string(tokens_[c]));
    return v;
  }
  double in_range(std::size_t c, double low, double high) const {
    const double v = number(c);
    if (!(v >= low && v <= high))
      fail(c, "must be in [" + format_double(low) + ", " + format_double(high) + "], got " + std::string(tokens_[c]));
    return v;
  }
  /// A 1-based point index in the file, 0-based in the result.
  int index(std::size_t c) const {
    const std::string range = "[1, " + std::to_string(vertex_count_) + "]";
    const double v = number(c);
    if (v != std::floor(v)) fail(c, "expected an integer point index in " + range + ", got " + quoted(tokens_[c]));
    if (!(v >= 1.0 && v <= static_cast<double>(vertex_count_)))
      fail(c, "index " + std::string(tokens_[c]) + " is out of range " + range +
                  (vertex_count_ == 0 ? " (the .vertex file has no vertices)" : ""));
    return static_cast<int>(v) - 1;
  }
  /// Fails unless the points of one spring or beam are distinct.
  void distinct(std::initializer_list<int> points, std::string_view what) const {
    for (auto a = points.begin(); a != points.end(); ++a)
      for (auto b = a + 1; b != points.end(); ++b)
        if (*a == *b) {
          std::string list;
          for (int p : points) list += (list.empty() ? "" : ", ") + std::to_string(p + 1);
          throw InputError(file_ + " line " + std::to_string(line_) + ": " + std::string(what) +
                           " needs distinct points, got " + list);
        }
  }

 private:
  [[noreturn]] void fail(std::size_t c, const std::string& what) const {
    throw InputError(file_ + " line " + std::to_string(line_) + " column " + std::to_string(c + 1) + " (" +
                     std::string(format_.columns[c]) + "): " + what);
  }

  const std::string& file_;
  const Format& format_;
  std::size_t line_;
  std::vector<std::string_view> tokens_;
  std::size_t vertex_count_;
};

/// The three points of a beam row (left, middle, right in columns 1–3), distinct.
template <typename Beam>
void read_beam_points(const Row& r, const char* what, Beam& beam) {
  beam.left = r.index(0);
  beam.middle = r.index(1);
  beam.right = r.index(2);
  r.distinct({beam.left, beam.middle, beam.right}, what);
}

/// Parses `text` in the file layout every kind shares (line 1 the row count, then that many rows,
/// blank lines only at the end) and hands each row, its column count checked, to `take`.
void parse_rows(const std::string& text, const std::string& file, const Format& format, std::size_t vertex_count,
                const std::function<void(const Row&)>& take) {
  std::string_view rest(text);
  std::size_t line_number = 0;
  std::optional<std::size_t> count;
  std::size_t rows = 0;
  std::size_t row_columns = 0;   // the column count of the first row (they must all have it)
  std::size_t first_blank = 0;   // the first blank line after line 1, 0 while none
  while (!rest.empty()) {
    const std::size_t newline = rest.find('\n');
    const std::string_view line = rest.substr(0, newline);
    rest = newline == std::string_view::npos ? std::string_view() : rest.substr(newline + 1);
    ++line_number;
    std::vector<std::string_view> tokens = split(line);
    const auto at_line = [&] { return file + " line " + std::to_string(line_number); };
    if (!count) {
      const std::string at = at_line();
      const std::string expected = ": expected the row count (one non-negative integer)";
      if (tokens.size() != 1)
        throw InputError(at + expected + ", got " + (tokens.empty() ? "a blank line" : quoted(line)));
      const std::string_view token = tokens[0];
      std::uintmax_t n = 0;
      const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), n);
      if (ec == std::errc::result_out_of_range || (ec == std::errc() && n > kMaxIb2dRows))
        throw InputError(at + ": row count " + quoted(token) + " is above the limit of " +
                         std::to_string(kMaxIb2dRows) + " rows");
      if (ec != std::errc() || end != token.data() + token.size())
        throw InputError(at + expected + ", got " + quoted(token));
      count = static_cast<std::size_t>(n);
      continue;
    }
    if (tokens.empty()) {
      if (first_blank == 0) first_blank = line_number;
      continue;
    }
    if (first_blank != 0)
      throw InputError(file + " line " + std::to_string(first_blank) +
                       ": blank line inside the data (blank lines are allowed only at the end)");
    ++rows;
    if (rows > *count) continue;  // counted for the message below, not read
    const std::size_t columns = tokens.size();
    if (columns < format.required_columns || columns > format.columns.size()) {
      const std::string all = std::to_string(format.columns.size());
      const std::string expected =
          format.required_columns == format.columns.size() ? all : std::to_string(format.required_columns) + " or " + all;
      throw InputError(at_line() + ": expected " + expected + " columns \"" + column_list(format) + "\", got " +
                       std::to_string(columns));
    }
    if (row_columns == 0) row_columns = columns;
    if (columns != row_columns)
      throw InputError(at_line() + ": has " + std::to_string(columns) + " columns, the rows above have " +
                       std::to_string(row_columns) + " (every row of a file has the same columns)");
    take(Row(file, format, line_number, std::move(tokens), vertex_count));
  }
  if (!count) throw InputError(file + " is empty: line 1 must hold the row count");
  if (rows != *count)
    throw InputError(file + ": line 1 says " + std::to_string(*count) + " rows, the file has " + std::to_string(rows));
}

/// Reads the file of `format` beside `stem` into `out` (nothing when an optional file is absent).
template <class T>
void read_list(const fs::path& stem, const Format& format, bool required, std::size_t vertex_count,
               std::vector<T>& out, const std::function<T(const Row&)>& convert) {
  const fs::path path = file_of(stem, format);
  const std::string file = shown(path, format);
  const std::optional<std::string> text = read_text(path, file, required);
  if (!text) return;
  parse_rows(*text, file, format, vertex_count, [&](const Row& row) { out.push_back(convert(row)); });
}

// ---- writing ----

/// Appends one row of values separated by single spaces.
class TextBuilder {
 public:
  explicit TextBuilder(std::size_t rows) { text_ = std::to_string(rows) + '\n'; }
  TextBuilder& index(int point) {
    separate();
    text_ += std::to_string(static_cast<long long>(point) + 1);
    return *this;
  }
  TextBuilder& number(double v) {
    separate();
    text_ += format_double(v);
    return *this;
  }
  void end_row() {
    text_ += '\n';
    fresh_ = true;
  }
  std::string take() { return std::move(text_); }

 private:
  void separate() {
    if (!fresh_) text_ += ' ';
    fresh_ = false;
  }
  std::string text_;
  bool fresh_ = true;
};

/// Checks a structure against the reader's rules before anything is written.
class StructureCheck {
 public:
  StructureCheck(const fs::path& stem, std::size_t vertex_count) : stem_(stem), vertex_count_(vertex_count) {}

  void rows(std::size_t n, std::string_view list) const {
    if (n > kMaxIb2dRows)
      fail(std::string(list) + " has " + std::to_string(n) + " entries; an IB2d file holds at most " +
           std::to_string(kMaxIb2dRows) + " rows");
  }
  void finite(double v, const std::string& where) const {
    if (!std::isfinite(v)) fail(where + " is " + format_double(v) + "; it must be finite");
  }
  void non_negative(double v, const std::string& where) const {
    if (!(v >= 0.0 && std::isfinite(v))) fail(where + " is " + format_double(v) + "; it must be finite and >= 0");
  }
  void index(int point, const std::string& where) const {
    if (point < 0 || static_cast<std::size_t>(point) >= vertex_count_)
      fail(where + " is " + std::to_string(point) + ", not a vertex index in [0, " + std::to_string(vertex_count_) +
           ")");
  }
  void distinct(std::initializer_list<int> points, const std::string& where) const {
    for (auto a = points.begin(); a != points.end(); ++a)
      for (auto b = a + 1; b != points.end(); ++b)
        if (*a == *b) fail(where + " joins point " + std::to_string(*a) + " to itself");
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError("cannot write the IB2d structure '" + stem_.string() + "': " + what);
  }

 private:
  const fs::path& stem_;
  std::size_t vertex_count_;
};

std::string item(std::string_view list, std::size_t k) { return std::string(list) + "[" + std::to_string(k) + "]"; }

void check_springs(const StructureCheck& check, const std::vector<Ib2dSpring>& springs, bool damped) {
  const std::string_view list = damped ? "damped_springs" : "springs";
  check.rows(springs.size(), list);
  for (std::size_t k = 0; k < springs.size(); ++k) {
    const Ib2dSpring& s = springs[k];
    const std::string at = item(list, k);
    check.index(s.master, at + ".master");
    check.index(s.slave, at + ".slave");
    check.distinct({s.master, s.slave}, at);
    check.non_negative(s.stiffness, at + ".stiffness");
    check.non_negative(s.rest_length, at + ".rest_length");
    if (damped) {
      check.non_negative(s.damping, at + ".damping");
      if (!(s.degree == 1.0))
        check.fail(at + ".degree is " + format_double(s.degree) + "; a .d_spring file has no alpha column (it must be 1)");
    } else {
      if (!(s.degree >= kMinDegree && s.degree <= kMaxDegree))
        check.fail(at + ".degree is " + format_double(s.degree) + "; it must be in [1, 10]");
      if (!(s.damping == 0.0))
        check.fail(at + ".damping is " + format_double(s.damping) +
                   "; a .spring file has no damping column (it must be 0; damped springs go in damped_springs)");
    }
  }
}

std::string springs_text(const std::vector<Ib2dSpring>& springs, bool damped) {
  bool with_degree = false;
  if (!damped)
    for (const Ib2dSpring& s : springs) with_degree = with_degree || s.degree != 1.0;
  TextBuilder out(springs.size());
  for (const Ib2dSpring& s : springs) {
    out.index(s.master).index(s.slave).number(s.stiffness).number(s.rest_length);
    if (damped) out.number(s.damping);
    if (with_degree) out.number(s.degree);
    out.end_row();
  }
  return out.take();
}

}  // namespace

std::vector<std::filesystem::path> ib2d_files_present(const std::filesystem::path& stem) {
  std::vector<fs::path> present;
  for (const Format* format : {&kVertex, &kSpring, &kDampedSpring, &kBeam, &kNonInvariantBeam, &kTarget}) {
    std::error_code ec;
    const fs::path path = file_of(stem, *format);
    if (fs::symlink_status(path, ec).type() != fs::file_type::not_found) present.push_back(path);  // as read_text tells
  }
  return present;
}

Ib2dStructure read_ib2d_structure(const std::filesystem::path& stem) {
  Ib2dStructure s;
  read_list<Vec2>(stem, kVertex, true, 0, s.vertices, [](const Row& r) { return Vec2{r.number(0), r.number(1)}; });
  const std::size_t n = s.vertices.size();
  read_list<Ib2dSpring>(stem, kSpring, false, n, s.springs, [](const Row& r) {
    Ib2dSpring spring;
    spring.master = r.index(0);
    spring.slave = r.index(1);
    r.distinct({spring.master, spring.slave}, "a spring");
    spring.stiffness = r.non_negative(2);
    spring.rest_length = r.non_negative(3);
    if (r.size() == 5) spring.degree = r.in_range(4, kMinDegree, kMaxDegree);
    return spring;
  });
  read_list<Ib2dSpring>(stem, kDampedSpring, false, n, s.damped_springs, [](const Row& r) {
    Ib2dSpring spring;
    spring.master = r.index(0);
    spring.slave = r.index(1);
    r.distinct({spring.master, spring.slave}, "a damped spring");
    spring.stiffness = r.non_negative(2);
    spring.rest_length = r.non_negative(3);
    spring.damping = r.non_negative(4);
    return spring;
  });
  read_list<Ib2dBeam>(stem, kBeam, false, n, s.beams, [](const Row& r) {
    Ib2dBeam beam;
    read_beam_points(r, "a beam", beam);
    beam.stiffness = r.non_negative(3);
    beam.curvature = r.number(4);
    return beam;
  });
  read_list<Ib2dNonInvariantBeam>(stem, kNonInvariantBeam, false, n, s.non_invariant_beams, [](const Row& r) {
    Ib2dNonInvariantBeam beam;
    read_beam_points(r, "a non-invariant beam", beam);
    beam.stiffness = r.non_negative(3);
    beam.curvature = {r.number(4), r.number(5)};
    return beam;
  });
  read_list<Ib2dTarget>(stem, kTarget, false, n, s.targets, [](const Row& r) {
    Ib2dTarget target;
    target.point = r.index(0);
    target.stiffness = r.non_negative(1);
    return target;
  });
  return s;
}

/// A beam's three points: vertex indices, distinct (the writer's side of read_beam_points).
template <typename Beam>
void check_beam_points(const StructureCheck& check, const Beam& b, const std::string& at) {
  check.index(b.left, at + ".left");
  check.index(b.middle, at + ".middle");
  check.index(b.right, at + ".right");
  check.distinct({b.left, b.middle, b.right}, at);
}

namespace {

/// Every field of the structure checked as the reader would check it (StructureCheck fails naming it).
void check_structure(const StructureCheck& check, const elastic::Ib2dStructure& s) {
  check.rows(s.vertices.size(), "vertices");
  for (std::size_t k = 0; k < s.vertices.size(); ++k) {
    check.finite(s.vertices[k].x, item("vertices", k) + ".x");
    check.finite(s.vertices[k].y, item("vertices", k) + ".y");
  }
  check_springs(check, s.springs, false);
  check_springs(check, s.damped_springs, true);
  check.rows(s.beams.size(), "beams");
  for (std::size_t k = 0; k < s.beams.size(); ++k) {
    const Ib2dBeam& b = s.beams[k];
    const std::string at = item("beams", k);
    check_beam_points(check, b, at);
    check.non_negative(b.stiffness, at + ".stiffness");
    check.finite(b.curvature, at + ".curvature");
  }
  check.rows(s.non_invariant_beams.size(), "non_invariant_beams");
  for (std::size_t k = 0; k < s.non_invariant_beams.size(); ++k) {
    const Ib2dNonInvariantBeam& b = s.non_invariant_beams[k];
    const std::string at = item("non_invariant_beams", k);
    check_beam_points(check, b, at);
    check.non_negative(b.stiffness, at + ".stiffness");
    check.finite(b.curvature.x, at + ".curvature.x");
    check.finite(b.curvature.y, at + ".curvature.y");
  }
  check.rows(s.targets.size(), "targets");
  for (std::size_t k = 0; k < s.targets.size(); ++k) {
    check.index(s.targets[k].point, item("targets", k) + ".point");
    check.non_negative(s.targets[k].stiffness, item("targets", k) + ".stiffness");
  }
}

/// One IB2d file of a structure: its kind, whether the structure has any (else a stale one is
/// removed) and its text.
struct Ib2dFileText {
  const Format* format;
  bool present;
  std::string text;
};

/// The files' texts, the .vertex file first.
std::vector<Ib2dFileText> structure_file_texts(const elastic::Ib2dStructure& s) {
  std::vector<Ib2dFileText> outputs;
  {
    TextBuilder out(s.vertices.size());
    for (const Vec2& v : s.vertices) {
      out.number(v.x).number(v.y);
      out.end_row();
    }
    outputs.push_back({&kVertex, true, out.take()});
  }
  outputs.push_back({&kSpring, !s.springs.empty(), springs_text(s.springs, false)});
  outputs.push_back({&kDampedSpring, !s.damped_springs.empty(), springs_text(s.damped_springs, true)});
  {
    TextBuilder out(s.beams.size());
    for (const Ib2dBeam& b : s.beams) {
      out.index(b.left).index(b.middle).index(b.right).number(b.stiffness).number(b.curvature);
      out.end_row();
    }
    outputs.push_back({&kBeam, !s.beams.empty(), out.take()});
  }
  {
    TextBuilder out(s.non_invariant_beams.size());
    for (const Ib2dNonInvariantBeam& b : s.non_invariant_beams) {
      out.index(b.left).index(b.middle).index(b.right).number(b.stiffness).number(b.curvature.x).number(b.curvature.y);
      out.end_row();
    }
    outputs.push_back({&kNonInvariantBeam, !s.non_invariant_beams.empty(), out.take()});
  }
  {
    TextBuilder out(s.targets.size());
    for (const Ib2dTarget& t : s.targets) {
      out.index(t.point).number(t.stiffness);
      out.end_row();
    }
    outputs.push_back({&kTarget, !s.targets.empty(), out.take()});
  }
  return outputs;
}

/// An optional file left from an earlier structure would be read back with this one: each must be
/// a file (or a link) that can be removed.
void check_stale_files(const std::filesystem::path& stem, const std::vector<Ib2dFileText>& outputs) {
  for (const Ib2dFileText& o : outputs) {
    if (o.present) continue;
    const fs::path path = file_of(stem, *o.format);
    std::error_code ec;
    const fs::file_status link = fs::symlink_status(path, ec);
    if (link.type() == fs::file_type::not_found) continue;
    if (ec) throw RunError("cannot write the IB2d structure '" + stem.string() + "': '" + path.string() + "': " + ec.message());
    if (!fs::is_regular_file(link) && !fs::is_symlink(link))
      throw RunError("cannot write the IB2d structure '" + stem.string() + "': '" + path.string() +
                     "' is in the way (it is " + type_name(link.type()) + ")");
  }
}

/// The optional files first, the .vertex file (the one a reader needs) last; stale ones removed.
void write_structure_files(const std::filesystem::path& stem, const std::vector<Ib2dFileText>& outputs) {
  for (auto o = outputs.rbegin(); o != outputs.rend(); ++o) {
    const fs::path path = file_of(stem, *o->format);
    if (o->present) {
      write_file_atomically(path, o->text);
      continue;
    }
    std::error_code ec;
    fs::remove(path, ec);  // no error when it is not there
    if (ec) throw RunError("cannot remove the stale '" + path.string() + "': " + ec.message());
  }
}

}  // namespace

void write_ib2d_structure(const elastic::Ib2dStructure& s, const std::filesystem::path& stem) {
  // Everything is checked and formatted first: a refused structure writes nothing.
  const StructureCheck check(stem, s.vertices.size());
  check_structure(check, s);
  const std::vector<Ib2dFileText> outputs = structure_file_texts(s);
  for (const Ib2dFileText& o : outputs)
    if (o.present && o.text.size() > kMaxIb2dFileBytes)
      check.fail("its " + std::string(o.format->extension) + " file would be " + std::to_string(o.text.size()) +
                 " bytes; the reader takes at most " + std::to_string(kMaxIb2dFileBytes));
  check_stale_files(stem, outputs);
  write_structure_files(stem, outputs);
}

}  // namespace jellysim::io
